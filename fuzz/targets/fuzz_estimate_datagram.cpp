// SPDX-License-Identifier: MIT
// Estimate datagram decoder (lib/include/jacobid/stream/estimate_datagram.hpp), as the host (64 joints)
// and a small controller build (4 joints) instantiate it. Properties: decode never reads outside the
// datagram (ASan), and a datagram it accepts re-encodes to exactly the same bytes (the format has one
// encoding per value, so anything else means a field was mis-read).
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

#include "fuzz_check.hpp"
#include "jacobid/stream/estimate_datagram.hpp"

using namespace jacobid;

namespace {

template <std::size_t MaxJoints>
void decode_and_reencode(const std::uint8_t* data, std::size_t size) {
    // A copy of exactly `size` bytes on the heap, so that ASan sees any read past the end.
    const std::vector<std::uint8_t> bytes(data, data + size);
    stream::EstimateDatagram<MaxJoints> d;
    if (stream::decode(Span<const std::uint8_t>(bytes.data(), bytes.size()), d) != stream::DatagramStatus::Ok) return;
    JACOBID_FUZZ_CHECK(d.joint_count >= 1 && d.joint_count <= MaxJoints, "accepted joint count outside 1..MaxJoints");
    std::vector<std::uint8_t> again(stream::datagram_size(d.joint_count, d.version));
    std::size_t written = 0;
    const stream::DatagramStatus status = stream::encode(d, Span<std::uint8_t>(again.data(), again.size()), written);
    JACOBID_FUZZ_CHECK(status == stream::DatagramStatus::Ok, "encode rejects a datagram that decode accepted");
    JACOBID_FUZZ_CHECK(written == size && std::memcmp(again.data(), data, size) == 0, "decode + encode does not give the same bytes");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    decode_and_reencode<64>(data, size);  // stream::kHostMaxJoints (host-tools)
    decode_and_reencode<4>(data, size);
    return 0;
}
