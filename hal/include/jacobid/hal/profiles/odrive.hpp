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
#include <cmath>
#include <cstdint>

#include "jacobid/hal/byte_codec.hpp"
#include "jacobid/hal/can_frame.hpp"
#include "jacobid/hal/joint_state.hpp"
#include "jacobid/hal/profiles/plausibility.hpp"
#include "jacobid/hal/unwrap.hpp"

namespace jacobid::hal::odrive {

constexpr std::uint8_t kGetEncoderEstimates = 0x009;
constexpr std::uint8_t kGetIq = 0x014;
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

class JointDecoder {
public:
    ConfigStatus configure(const JointConfig& c) noexcept {
        const ConfigStatus s = validate(c);
        if (s == ConfigStatus::Ok) {
            config_ = c;
            unwrap_.set_period(c.position_wrap_turns);
        }
        return s;
    }
    const JointConfig& config() const noexcept { return config_; }
    void reset() noexcept { unwrap_.reset(); }

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
            PeriodUnwrapper next = unwrap_;  // moved only by a frame that passes every check
            const double position = link_position(m, kTwoPi * next.update(static_cast<double>(e.position_turns)));
            if (!std::isfinite(position)) return DecodeStatus::OutOfRange;
            unwrap_ = next;
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

private:
    JointConfig config_{};
    PeriodUnwrapper unwrap_{};
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

}  // namespace jacobid::hal::odrive
