// SPDX-License-Identifier: MIT
// CiA 402 TPDO decoder (hal/include/jacobid/hal/profiles/cia402.hpp): fuzzed node id, PDO layout, scales
// and modulo range, then fuzzed frames on (mostly) the PDO's COB-ID. Properties: decoder_properties.hpp.
#include <cstddef>
#include <cstdint>

#include "decoder_properties.hpp"
#include "jacobid/hal/profiles/cia402.hpp"

using namespace jacobid;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    FuzzedDataProvider in(data, size);
    hal::cia402::JointConfig c;
    c.node_id = in.ConsumeIntegral<std::uint8_t>();
    c.layout.cob_id = in.ConsumeBool() ? 0u : in.ConsumeIntegral<std::uint32_t>();
    c.layout.position_byte = in.ConsumeIntegralInRange<std::uint8_t>(0, 9);
    c.layout.effort = in.PickValueInArray({hal::cia402::EffortObject::None, hal::cia402::EffortObject::CurrentActual,
                                           hal::cia402::EffortObject::TorqueActual});
    c.layout.effort_byte = in.ConsumeIntegralInRange<std::uint8_t>(0, 9);
    c.counts_per_revolution = fuzz::pick_double(in, std::array<double, 3>{65536.0, 4096.0, -10000.0});
    c.position_modulus = in.ConsumeBool() ? (1ull << 32) : in.ConsumeIntegralInRange<std::uint64_t>(0, (1ull << 32) + 1);
    c.rated_current = fuzz::pick_double(in, std::array<double, 2>{3.0, 0.0});
    c.rated_torque = fuzz::pick_double(in, std::array<double, 2>{2.0, 0.0});
    c.max_abs_per_mille = in.ConsumeBool() ? 10000 : in.ConsumeIntegral<int>();
    c.mapping = fuzz::consume_mapping(in);

    hal::cia402::JointDecoder decoder;
    if (decoder.configure(c) != hal::ConfigStatus::Ok) return 0;
    hal::JointState state;
    while (in.remaining_bytes() > 0) fuzz::check_decode(decoder, fuzz::consume_frame(in, c.cob_id(), false), state, c.mapping);
    return 0;
}
