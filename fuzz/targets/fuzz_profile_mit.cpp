// SPDX-License-Identifier: MIT
// MIT-mode reply decoder (hal/include/jacobid/hal/profiles/mit.hpp): a fuzzed joint configuration, then a
// stream of fuzzed frames on (mostly) its reply id. Properties: decoder_properties.hpp.
#include <cstddef>
#include <cstdint>

#include "decoder_properties.hpp"
#include "jacobid/hal/profiles/mit.hpp"

using namespace jacobid;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    FuzzedDataProvider in(data, size);
    hal::mit::JointConfig c;
    c.extended_id = in.ConsumeBool();
    c.reply_can_id = in.ConsumeIntegralInRange<int>(0, 3) == 0 ? in.ConsumeIntegral<std::uint32_t>() : in.ConsumeIntegralInRange<std::uint32_t>(0, 0x7FF);
    c.motor_id = in.ConsumeIntegral<std::uint8_t>();
    c.ranges.p_min = fuzz::pick_double(in, std::array<double, 2>{-12.5, -95.5});
    c.ranges.p_max = fuzz::pick_double(in, std::array<double, 2>{12.5, 95.5});
    c.ranges.v_min = fuzz::pick_double(in, std::array<double, 2>{-50.0, -65.0});
    c.ranges.v_max = fuzz::pick_double(in, std::array<double, 2>{50.0, 65.0});
    c.ranges.t_min = fuzz::pick_double(in, std::array<double, 2>{-18.0, -30.0});
    c.ranges.t_max = fuzz::pick_double(in, std::array<double, 2>{18.0, 30.0});
    c.effort = in.ConsumeBool() ? hal::EffortKind::Current : hal::EffortKind::Torque;
    c.require_status = in.ConsumeBool();
    c.temperature_offset = in.ConsumeIntegral<int>();
    c.mapping = fuzz::consume_mapping(in);

    hal::mit::JointDecoder decoder;
    if (decoder.configure(c) != hal::ConfigStatus::Ok) return 0;
    hal::JointState state;
    while (in.remaining_bytes() > 0) {
        hal::CanFrame f = fuzz::consume_frame(in, c.reply_can_id, c.extended_id);
        if (in.ConsumeIntegralInRange<int>(0, 3) != 0) f.data[0] = c.motor_id;  // mostly this motor's replies
        fuzz::check_decode(decoder, f, state, c.mapping);
    }
    return 0;
}
