// SPDX-License-Identifier: MIT
#pragma once
// ODrive CANSimple (ODrive firmware 0.5 / 0.6): 11-bit id = node_id << 5 | command id, payload
// little-endian.
//   0x009 Get_Encoder_Estimates: bytes 0..3 Pos_Estimate float32 (turns), 4..7 Vel_Estimate float32 (turns/s)
//   0x014 Get_Iq:                bytes 0..3 Iq_Setpoint float32 (A),     4..7 Iq_Measured float32 (A)
// Both are cyclic messages (encoder_msg_rate_ms / iq_msg_rate_ms) or answers to a remote request.
//
// Conversions: motor angle = 2 pi * turns; link torque = Kt * Iq_measured * N (joint_state.hpp), with
// ODrive's torque_constant = 8.27 / Kv for Kt. Pos_Estimate is continuous (multi-turn) unless the
// axis uses circular setpoints, where it wraps every position_wrap_turns (usually 1): then it is unwrapped.
// Note that a float32 turn count loses resolution as it grows (2^-23 relative: 1e-4 turn at 1000 turns).
//
// Commands (controller -> axis, ODrive CANSimple "Set_*" messages, little-endian):
//   0x007 Set_Axis_State:   bytes 0..3 Axis_Requested_State uint32 (8 CLOSED_LOOP_CONTROL, 1 IDLE)
//   0x00C Set_Input_Pos:    bytes 0..3 Input_Pos float32 (turns), 4..5 Vel_FF int16 (0.001 turn/s),
//                           6..7 Torque_FF int16 (0.001 N.m)
//   0x00E Set_Input_Torque: bytes 0..3 Input_Torque float32 (N.m)
// Torques are motor side (ODrive divides by its torque_constant); the feed-forwards saturate at the
// int16 range (+-32.767 turn/s, +-32.767 N.m). Byte layout: docs/profiles.md, "ODrive CANSimple".
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "jacobid/hal/profiles/profile_entry.hpp"

namespace jacobid::hal::odrive {

constexpr std::uint8_t kGetEncoderEstimates = 0x009;
constexpr std::uint8_t kGetIq = 0x014;
constexpr std::uint8_t kSetAxisState = 0x007;
constexpr std::uint8_t kSetInputPos = 0x00C;
constexpr std::uint8_t kSetInputTorque = 0x00E;
constexpr std::uint32_t kAxisStateIdle = 1;
constexpr std::uint32_t kAxisStateClosedLoopControl = 8;
constexpr std::uint8_t kMaxNodeId = 0x3F;  // 6 bits above the 5-bit command

constexpr std::uint32_t can_id(std::uint8_t node_id, std::uint8_t command) noexcept {
    return (static_cast<std::uint32_t>(node_id) << 5) | (command & 0x1Fu);
}
constexpr std::uint8_t node_of(std::uint32_t id) noexcept { return static_cast<std::uint8_t>((id >> 5) & 0x3Fu); }
constexpr std::uint8_t command_of(std::uint32_t id) noexcept { return static_cast<std::uint8_t>(id & 0x1Fu); }

struct EncoderEstimates {
    float position_turns = 0.0f;
    float velocity_turns_s = 0.0f;
};
struct Iq {
    float setpoint = 0.0f;  // A
    float measured = 0.0f;  // A
};

// Two float32 fields: shared layout check of both messages. Non-finite values are rejected: ODrive
// never sends them for valid estimates, so they mean corruption or an uncalibrated axis.
inline DecodeStatus unpack_two_floats(const CanFrame& f, float& a, float& b) noexcept {
    if (f.remote() || f.fd() || f.error() || f.extended() || f.len > kCanMaxDataLength) return DecodeStatus::Malformed;
    if (f.len < 8) return DecodeStatus::Short;
    a = load_float32_le(&f.data[0]);
    b = load_float32_le(&f.data[4]);
    if (!std::isfinite(a) || !std::isfinite(b)) return DecodeStatus::OutOfRange;
    return DecodeStatus::Ok;
}

inline DecodeStatus unpack_encoder_estimates(const CanFrame& f, EncoderEstimates& out) noexcept {
    return unpack_two_floats(f, out.position_turns, out.velocity_turns_s);
}
inline DecodeStatus unpack_iq(const CanFrame& f, Iq& out) noexcept { return unpack_two_floats(f, out.setpoint, out.measured); }

inline void pack_two_floats(std::uint32_t id, float a, float b, CanFrame& f) noexcept {
    f = CanFrame{};
    f.id = id;
    f.len = 8;
    store_float32_le(&f.data[0], a);
    store_float32_le(&f.data[4], b);
}
inline void pack_encoder_estimates(std::uint8_t node, const EncoderEstimates& e, CanFrame& f) noexcept {
    pack_two_floats(can_id(node, kGetEncoderEstimates), e.position_turns, e.velocity_turns_s, f);
}
inline void pack_iq(std::uint8_t node, const Iq& iq, CanFrame& f) noexcept {
    pack_two_floats(can_id(node, kGetIq), iq.setpoint, iq.measured, f);
}

struct JointConfig {
    std::uint8_t node_id = 0;           // 0..63
    double position_wrap_turns = 0.0;   // 0: continuous Pos_Estimate; 1: circular setpoints
    JointMapping mapping{};             // torque_constant = Kt (8.27 / Kv), required
};

inline ConfigStatus validate(const JointConfig& c) noexcept {
    if (c.node_id > kMaxNodeId) return ConfigStatus::InvalidNodeId;
    if (!std::isfinite(c.position_wrap_turns) || c.position_wrap_turns < 0.0) return ConfigStatus::InvalidScale;
    return validate(c.mapping, EffortKind::Current);
}

// Defaults of joint `index` (0-based), the same for jacobid-fw and sim-can (docs/firmware.md): node
// index + 1, encoder estimates and Iq; Kt 0.083 N.m/A (8.27 / Kv, Kv = 100 rpm/V); gear ratio 4.
inline void apply_firmware_defaults(JointConfig& c, std::size_t index) noexcept {
    c.node_id = static_cast<std::uint8_t>(index + 1);
    c.mapping.torque_constant = 8.27 / 100.0;
    c.mapping.gear_ratio = 4.0;
}

template <typename Fields>
void read_config(Fields& s, JointConfig& c) {
    c.node_id = static_cast<std::uint8_t>(s.integer("node_id", c.node_id, 0, kMaxNodeId));
    c.position_wrap_turns = s.number("position_wrap_turns", c.position_wrap_turns);
    c.mapping = read_mapping(s, c.mapping);
}

inline const char* config_key_of(const JointConfig&, ConfigStatus s) noexcept {
    if (const char* k = mapping_key_of(s)) return k;
    return s == ConfigStatus::InvalidNodeId ? "node_id" : s == ConfigStatus::InvalidScale ? "position_wrap_turns" : "profile";
}

// Pos_Estimate wraps every position_wrap_turns turns (0: continuous).
inline double unwrap_period(const JointConfig& c) noexcept { return c.position_wrap_turns; }

class JointDecoder : public JointDecoderBase<JointConfig, PeriodUnwrapper> {
public:
    // The one test of "is this frame mine" (docs/profiles.md): every caller goes through decode.
    DecodeStatus decode(const CanFrame& f, JointState& s) noexcept {
        if (f.extended() || node_of(f.id) != config_.node_id || (f.id & ~kCanStandardIdMask) != 0) return DecodeStatus::NotMine;
        const std::uint8_t cmd = command_of(f.id);
        if (cmd != kGetEncoderEstimates && cmd != kGetIq) return DecodeStatus::NotMine;  // other messages of the node
        const JointMapping& m = config_.mapping;
        if (cmd == kGetEncoderEstimates) {
            EncoderEstimates e;
            if (const DecodeStatus st = unpack_encoder_estimates(f, e); st != DecodeStatus::Ok) return st;
            const double v = link_velocity(m, kTwoPi * static_cast<double>(e.velocity_turns_s));
            if (!plausible(v, m.max_abs_velocity)) return DecodeStatus::OutOfRange;
            double position = 0.0;
            const auto to_link = [&](double turns) { return link_position(m, kTwoPi * turns); };
            if (!commit_position(static_cast<double>(e.position_turns), to_link, position)) return DecodeStatus::OutOfRange;
            s.position = position;
            s.velocity = v;
            mark_position(s, f.timestamp_ns);
            return DecodeStatus::Ok;
        }
        Iq iq;
        if (const DecodeStatus st = unpack_iq(f, iq); st != DecodeStatus::Ok) return st;
        const double tau = link_torque(m, EffortKind::Current, static_cast<double>(iq.measured));
        if (!plausible(tau, m.max_abs_torque)) return DecodeStatus::OutOfRange;
        s.torque = tau;
        mark_torque(s, f.timestamp_ns);
        return DecodeStatus::Ok;
    }
};

// Simulator side. The Iq setpoint is reported equal to the measured current.
inline void encode_encoder_estimates(const JointConfig& c, double link_q, double link_qd, CanFrame& f) noexcept {
    double turns = motor_position(c.mapping, link_q) / kTwoPi;
    if (c.position_wrap_turns > 0.0) turns -= c.position_wrap_turns * std::floor(turns / c.position_wrap_turns);
    pack_encoder_estimates(c.node_id, {static_cast<float>(turns), static_cast<float>(motor_velocity(c.mapping, link_qd) / kTwoPi)}, f);
}
inline void encode_iq(const JointConfig& c, double link_tau, CanFrame& f) noexcept {
    const auto i = static_cast<float>(device_effort(c.mapping, EffortKind::Current, link_tau));
    pack_iq(c.node_id, {i, i}, f);
}

// --- commands (controller -> axis) ---

struct InputPos {
    float position_turns = 0.0f;
    std::int16_t velocity_ff = 0;  // 0.001 turn/s
    std::int16_t torque_ff = 0;    // 0.001 N.m
};

inline void pack_input_pos(std::uint8_t node, const InputPos& r, CanFrame& f) noexcept {
    f = CanFrame{};
    f.id = can_id(node, kSetInputPos);
    f.len = 8;
    store_float32_le(&f.data[0], r.position_turns);
    store_uint(&f.data[4], 2, ByteOrder::LittleEndian, static_cast<std::uint16_t>(r.velocity_ff));
    store_uint(&f.data[6], 2, ByteOrder::LittleEndian, static_cast<std::uint16_t>(r.torque_ff));
}
inline void pack_input_torque(std::uint8_t node, float torque, CanFrame& f) noexcept {
    f = CanFrame{};
    f.id = can_id(node, kSetInputTorque);
    f.len = 4;
    store_float32_le(&f.data[0], torque);
}
inline void pack_axis_state(std::uint8_t node, std::uint32_t requested_state, CanFrame& f) noexcept {
    f = CanFrame{};
    f.id = can_id(node, kSetAxisState);
    f.len = 4;
    store_uint(&f.data[0], 4, ByteOrder::LittleEndian, requested_state);
}

// Drive side (sim-can): layout only.
inline DecodeStatus unpack_input_pos(const CanFrame& f, InputPos& out) noexcept {
    if (f.remote() || f.fd() || f.error() || f.extended() || f.len > kCanMaxDataLength) return DecodeStatus::Malformed;
    if (f.len < 8) return DecodeStatus::Short;
    out.position_turns = load_float32_le(&f.data[0]);
    out.velocity_ff = static_cast<std::int16_t>(sign_extend(load_uint(&f.data[4], 2, ByteOrder::LittleEndian), 16));
    out.torque_ff = static_cast<std::int16_t>(sign_extend(load_uint(&f.data[6], 2, ByteOrder::LittleEndian), 16));
    return std::isfinite(out.position_turns) ? DecodeStatus::Ok : DecodeStatus::OutOfRange;
}

// Nearest multiple of 0.001, saturated to int16 (NaN gives 0: no feed-forward rather than a jump).
inline std::int16_t to_milli_int16(double x) noexcept {
    const double r = std::round(x * 1000.0);
    if (!(r == r)) return 0;
    return static_cast<std::int16_t>(r > 32767.0 ? 32767.0 : (r < -32768.0 ? -32768.0 : r));
}

// Link-side command -> Set_Input_Pos (Position mode) or Set_Input_Torque (Torque mode). With circular
// setpoints the position is sent wrapped to [0, position_wrap_turns), as the axis expects it.
inline std::size_t encode_command(const JointConfig& c, const JointCommand& cmd, CanFrame* out) noexcept {
    const JointMapping& m = c.mapping;
    const double motor_torque = device_effort(m, EffortKind::Torque, cmd.torque);
    if (cmd.mode == CommandMode::Torque) {
        pack_input_torque(c.node_id, static_cast<float>(motor_torque), out[0]);
        return 1;
    }
    double turns = motor_position(m, cmd.position) / kTwoPi;
    if (c.position_wrap_turns > 0.0) turns -= c.position_wrap_turns * std::floor(turns / c.position_wrap_turns);
    InputPos r;
    r.position_turns = static_cast<float>(turns);
    r.velocity_ff = to_milli_int16(motor_velocity(m, cmd.velocity) / kTwoPi);
    r.torque_ff = to_milli_int16(motor_torque);
    pack_input_pos(c.node_id, r, out[0]);
    return 1;
}

// Drive side (a simulated axis following commands): Set_Input_Pos or Set_Input_Torque of this node as
// a link-side JointCommand; only the fields the message carries (and the mode) are written.
inline DecodeStatus decode_command(const JointConfig& c, CommandMode /*drive_mode*/, const CanFrame& f, JointCommand& out) noexcept {
    if (f.extended() || (f.id & ~kCanStandardIdMask) != 0 || node_of(f.id) != c.node_id) return DecodeStatus::NotMine;
    const JointMapping& m = c.mapping;
    if (command_of(f.id) == kSetInputPos) {
        InputPos r;
        if (const DecodeStatus st = unpack_input_pos(f, r); st != DecodeStatus::Ok) return st;
        out.mode = CommandMode::Position;
        out.position = link_position(m, kTwoPi * static_cast<double>(r.position_turns));
        out.velocity = link_velocity(m, kTwoPi * 0.001 * r.velocity_ff);
        out.torque = link_torque(m, EffortKind::Torque, 0.001 * r.torque_ff);
        return DecodeStatus::Ok;
    }
    if (command_of(f.id) != kSetInputTorque) return DecodeStatus::NotMine;  // other messages of the node
    if (f.remote() || f.fd() || f.error() || f.len > kCanMaxDataLength) return DecodeStatus::Malformed;
    if (f.len < 4) return DecodeStatus::Short;
    const float torque = load_float32_le(&f.data[0]);
    if (!std::isfinite(torque)) return DecodeStatus::OutOfRange;
    out.mode = CommandMode::Torque;
    out.torque = link_torque(m, EffortKind::Torque, static_cast<double>(torque));
    return DecodeStatus::Ok;
}

// The registry's drive side (profile_entry.hpp): one sample is both messages.
inline std::size_t encode_telemetry(const JointConfig& c, double q, double qd, double tau, CanFrame* out) noexcept {
    encode_encoder_estimates(c, q, qd, out[0]);
    encode_iq(c, tau, out[1]);
    return 2;
}

// The registry entry (hal/profile_registry.hpp, docs/profiles.md).
struct Profile : ProfileEntry<JointConfig, JointDecoder, 2, true> {
    static constexpr const char* kName = "odrive";
};

}  // namespace jacobid::hal::odrive
