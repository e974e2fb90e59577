// SPDX-License-Identifier: MIT
// Generic signal decoder (hal/include/jacobid/hal/profiles/generic.hpp): fuzzed bit-field layouts of
// position, velocity and effort (shared or separate frames), then fuzzed frames on (mostly) their ids.
// Properties: decoder_properties.hpp.
#include <cstddef>
#include <cstdint>

#include "decoder_properties.hpp"
#include "jacobid/hal/profiles/generic.hpp"

using namespace jacobid;

namespace {

hal::generic::Signal consume_signal(FuzzedDataProvider& in, std::uint32_t id) {
    hal::generic::Signal s;
    s.can_id = in.ConsumeIntegralInRange<int>(0, 3) == 0 ? in.ConsumeIntegral<std::uint32_t>() : id;
    s.extended_id = in.ConsumeIntegralInRange<int>(0, 3) == 0;
    s.byte_offset = in.ConsumeIntegralInRange<std::uint8_t>(0, 65);
    s.bit_width = in.ConsumeIntegralInRange<std::uint8_t>(0, 65);
    s.bit_shift = in.ConsumeIntegralInRange<std::uint8_t>(0, 8);
    s.is_signed = in.ConsumeBool();
    s.order = in.ConsumeBool() ? hal::ByteOrder::LittleEndian : hal::ByteOrder::BigEndian;
    s.scale = fuzz::pick_double(in, std::array<double, 3>{1e-3, 9.587379924285257e-5, -0.01});
    s.offset = fuzz::pick_double(in, std::array<double, 2>{0.0, -3.0});
    s.check_raw_range = in.ConsumeBool();
    s.raw_min = in.ConsumeIntegral<std::int64_t>();
    s.raw_max = in.ConsumeIntegral<std::int64_t>();
    return s;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    FuzzedDataProvider in(data, size);
    const std::uint32_t id = in.ConsumeIntegralInRange<std::uint32_t>(0, 0x7FF);
    hal::generic::JointConfig c;
    c.position = consume_signal(in, id);
    c.unwrap_position = in.ConsumeBool();
    c.has_velocity = in.ConsumeBool();
    c.velocity = consume_signal(in, id + (in.ConsumeBool() ? 1u : 0u));
    c.has_effort = in.ConsumeBool();
    c.effort = consume_signal(in, id + (in.ConsumeBool() ? 1u : 0u));
    c.effort_kind = in.ConsumeBool() ? hal::EffortKind::Current : hal::EffortKind::Torque;
    c.mapping = fuzz::consume_mapping(in);

    hal::generic::JointDecoder decoder;
    if (decoder.configure(c) != hal::ConfigStatus::Ok) return 0;
    hal::JointState state;
    while (in.remaining_bytes() > 0) {
        const std::uint32_t frame_id = id + (in.ConsumeBool() ? 1u : 0u);
        fuzz::check_decode(decoder, fuzz::consume_frame(in, frame_id, c.position.extended_id), state, c.mapping);
    }
    return 0;
}
