// SPDX-License-Identifier: MIT
// ODrive CAN-simple decoder (hal/include/jacobid/hal/profiles/odrive.hpp): fuzzed node id and wrap period,
// then fuzzed encoder-estimate / Iq frames (mostly) of that node. Properties: decoder_properties.hpp.
#include <cstddef>
#include <cstdint>

#include "decoder_properties.hpp"
#include "jacobid/hal/profiles/odrive.hpp"

using namespace jacobid;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    FuzzedDataProvider in(data, size);
    hal::odrive::JointConfig c;
    c.node_id = in.ConsumeIntegralInRange<std::uint8_t>(0, 70);
    c.position_wrap_turns = fuzz::pick_double(in, std::array<double, 3>{0.0, 1.0, 0.25});
    c.mapping = fuzz::consume_mapping(in);

    hal::odrive::JointDecoder decoder;
    if (decoder.configure(c) != hal::ConfigStatus::Ok) return 0;
    hal::JointState state;
    while (in.remaining_bytes() > 0) {
        const std::uint8_t command = in.ConsumeBool() ? hal::odrive::kGetEncoderEstimates : hal::odrive::kGetIq;
        fuzz::check_decode(decoder, fuzz::consume_frame(in, hal::odrive::can_id(c.node_id, command), false), state, c.mapping);
    }
    return 0;
}
