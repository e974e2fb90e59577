// SPDX-License-Identifier: MIT
#pragma once
// MIT mode reply (mini-cheetah motor controller; T-Motor AK and CubeMars actuators in MIT mode).
//
// Reply layout (big-endian bit fields, the mini-cheetah firmware's pack_reply()):
//   data[0]      motor (driver) id: every motor replies on the same CAN id, so data[0] demultiplexes
//   data[1..2]   position  16 bit, p = p_min + code * (p_max - p_min) / 65535
//   data[3]      velocity  bits 11..4
//   data[4]      velocity  bits 3..0 (high nibble) | effort bits 11..8 (low nibble)
//   data[5]      effort    bits 7..0; 12-bit codes scale like the position over (v_min, v_max), (t_min, t_max)
//   data[6]      temperature (AK/CubeMars only): raw - temperature_offset degC (CubeMars documents +40)
//   data[7]      error code  (AK/CubeMars only): 0 none, 1 over-temperature, 2 over-current, ...
// The mini-cheetah sends 6 bytes, AK/CubeMars 8. The effort field is a torque (N.m, the AK ranges) or a
// q-axis current (A) depending on the firmware: EffortKind says which.
//
// Wrapping: the firmware computes the position code as (int)((p - p_min) * 65535 / span) and keeps only
// its low 16 bits, so a position beyond the range wraps modulo 65536 codes (period 65536 * span / 65535
// rad, a hair over the span). Unwrapping is therefore done on the code, exactly, before scaling.
#include <cmath>
#include <cstdint>

#include "jacobid/hal/can_frame.hpp"
#include "jacobid/hal/joint_state.hpp"
#include "jacobid/hal/profiles/plausibility.hpp"
#include "jacobid/hal/unwrap.hpp"

namespace jacobid::hal::mit {

constexpr unsigned kPositionBits = 16;
constexpr unsigned kVelocityBits = 12;
constexpr unsigned kEffortBits = 12;
constexpr std::uint8_t kShortReplyLength = 6;   // mini-cheetah: id, position, velocity, effort
constexpr std::uint8_t kStatusReplyLength = 8;  // AK / CubeMars: + temperature, error

struct Ranges {
    double p_min = -12.5, p_max = 12.5;  // rad
    double v_min = -50.0, v_max = 50.0;  // rad/s
    double t_min = -18.0, t_max = 18.0;  // N.m (or A with EffortKind::Current)
};
// Defaults of common actuators (manufacturer ranges of the MIT-mode scaling, output side).
constexpr Ranges kAk80_9{-12.5, 12.5, -50.0, 50.0, -18.0, 18.0};
constexpr Ranges kMiniCheetah{-12.5, 12.5, -65.0, 65.0, -18.0, 18.0};  // v/t: per-build firmware constants

inline ConfigStatus validate(const Ranges& r) noexcept {
    // The span hi - lo must be finite too: it scales every code (-1e308..1e308 would overflow it).
    auto ok = [](double lo, double hi) { return std::isfinite(lo) && std::isfinite(hi) && lo < hi && std::isfinite(hi - lo); };
    return ok(r.p_min, r.p_max) && ok(r.v_min, r.v_max) && ok(r.t_min, r.t_max) ? ConfigStatus::Ok : ConfigStatus::InvalidRange;
}

// Linear scaling of the mini-cheetah's uint_to_float: code 0 is `lo`, the largest code is `hi`.
inline double code_to_value(std::uint32_t code, double lo, double hi, unsigned bits) noexcept {
    return lo + static_cast<double>(code) * (hi - lo) / static_cast<double>((1u << bits) - 1u);
}
// Inverse, clamped to the range (for velocity and effort: the firmware saturates them).
inline std::uint32_t value_to_code(double x, double lo, double hi, unsigned bits) noexcept {
    const double max_code = static_cast<double>((1u << bits) - 1u);
    double c = std::round((x - lo) * max_code / (hi - lo));
    if (!(c >= 0.0)) c = 0.0;  // also NaN
    if (c > max_code) c = max_code;
    return static_cast<std::uint32_t>(c);
}
// Position code with the firmware's wrap: any (multi-turn) position maps into 0..65535.
inline std::uint16_t position_to_code(double p, const Ranges& r) noexcept {
    const double c = std::round((p - r.p_min) * 65535.0 / (r.p_max - r.p_min));
    if (!std::isfinite(c)) return 0;
    const double wrapped = c - 65536.0 * std::floor(c / 65536.0);
    return static_cast<std::uint16_t>(wrapped);
}

// The fields exactly as on the wire.
struct RawReply {
    std::uint8_t motor_id = 0;
    std::uint16_t position = 0;  // 16 bit
    std::uint16_t velocity = 0;  // 12 bit
    std::uint16_t effort = 0;    // 12 bit
    bool has_status = false;     // temperature and error present (8-byte reply)
    std::uint8_t temperature = 0;
    std::uint8_t error = 0;
};

// Layout only: checks the frame type and length. Does not look at the CAN id.
inline DecodeStatus unpack_reply(const CanFrame& f, RawReply& out) noexcept {
    if (f.remote() || f.fd() || f.error() || f.len > kCanMaxDataLength) return DecodeStatus::Malformed;
    if (f.len < kShortReplyLength) return DecodeStatus::Short;
    const auto* d = f.data.data();
    out.motor_id = d[0];
    out.position = static_cast<std::uint16_t>((d[1] << 8) | d[2]);
    out.velocity = static_cast<std::uint16_t>((d[3] << 4) | (d[4] >> 4));
    out.effort = static_cast<std::uint16_t>(((d[4] & 0x0F) << 8) | d[5]);
    out.has_status = f.len >= kStatusReplyLength;
    out.temperature = out.has_status ? d[6] : 0;
    out.error = out.has_status ? d[7] : 0;
    return DecodeStatus::Ok;
}

inline void pack_reply(const RawReply& r, std::uint32_t can_id, bool extended, CanFrame& f) noexcept {
    f = CanFrame{};
    f.id = can_id;
    f.flags = extended ? kCanExtended : 0;
    f.len = r.has_status ? kStatusReplyLength : kShortReplyLength;
    auto* d = f.data.data();
    d[0] = r.motor_id;
    d[1] = static_cast<std::uint8_t>(r.position >> 8);
    d[2] = static_cast<std::uint8_t>(r.position & 0xFF);
    d[3] = static_cast<std::uint8_t>((r.velocity >> 4) & 0xFF);
    d[4] = static_cast<std::uint8_t>(((r.velocity & 0x0F) << 4) | ((r.effort >> 8) & 0x0F));
    d[5] = static_cast<std::uint8_t>(r.effort & 0xFF);
    if (r.has_status) {
        d[6] = r.temperature;
        d[7] = r.error;
    }
}

struct JointConfig {
    std::uint32_t reply_can_id = 0;  // the id every motor replies on (mini-cheetah: the master id, 0)
    bool extended_id = false;
    std::uint8_t motor_id = 1;       // data[0] of this joint's replies
    Ranges ranges = kAk80_9;
    EffortKind effort = EffortKind::Torque;
    bool require_status = false;     // reject 6-byte replies: set when the motor is known to send 8
    int temperature_offset = 40;     // degC = data[6] - offset
    JointMapping mapping{};          // device side = the reported (output shaft) values
};

inline ConfigStatus validate(const JointConfig& c) noexcept {
    if ((c.reply_can_id & ~(c.extended_id ? kCanExtendedIdMask : kCanStandardIdMask)) != 0) return ConfigStatus::InvalidCanId;
    if (const ConfigStatus s = validate(c.ranges); s != ConfigStatus::Ok) return s;
    return validate(c.mapping, c.effort);
}

// Joint side of the profile: claims this motor's replies, unwraps, scales and maps to the link side.
class JointDecoder {
public:
    JointDecoder() noexcept : unwrap_(1u << kPositionBits) {}

    ConfigStatus configure(const JointConfig& c) noexcept {
        const ConfigStatus s = validate(c);
        if (s == ConfigStatus::Ok) {
            config_ = c;
            unwrap_.set_modulus(1u << kPositionBits);
        }
        return s;
    }
    const JointConfig& config() const noexcept { return config_; }
    void reset() noexcept { unwrap_.reset(); }

    DecodeStatus decode(const CanFrame& f, JointState& s) noexcept {
        if (f.id != config_.reply_can_id || f.extended() != config_.extended_id) return DecodeStatus::NotMine;
        // A frame too short to carry data[0] cannot be told apart: the first joint on the id reports it.
        if (f.len >= 1 && !f.remote() && f.data[0] != config_.motor_id) return DecodeStatus::NotMine;
        RawReply r;
        if (const DecodeStatus st = unpack_reply(f, r); st != DecodeStatus::Ok) return st;
        if (config_.require_status && !r.has_status) return DecodeStatus::Short;
        const JointMapping& m = config_.mapping;
        const Ranges& g = config_.ranges;
        const double v = link_velocity(m, code_to_value(r.velocity, g.v_min, g.v_max, kVelocityBits));
        const double tau = link_torque(m, config_.effort, code_to_value(r.effort, g.t_min, g.t_max, kEffortBits));
        if (!plausible(v, m.max_abs_velocity) || !plausible(tau, m.max_abs_torque)) return DecodeStatus::OutOfRange;
        // Only a frame that passed every check moves the unwrapper: a rejected one must not count a turn.
        CountUnwrapper next = unwrap_;
        const std::int64_t code = next.update(r.position);
        const double motor_p = g.p_min + static_cast<double>(code) * (g.p_max - g.p_min) / 65535.0;
        const double position = link_position(m, motor_p);
        if (!std::isfinite(position)) return DecodeStatus::OutOfRange;
        unwrap_ = next;
        s.position = position;
        s.velocity = v;
        s.torque = tau;
        if (r.has_status) {
            // In 64 bits and clamped: any int offset is accepted, and raw - offset must not overflow.
            const std::int64_t t = static_cast<std::int64_t>(r.temperature) - config_.temperature_offset;
            s.temperature_c = static_cast<std::int16_t>(t < INT16_MIN ? INT16_MIN : (t > INT16_MAX ? INT16_MAX : t));
            s.device_error = r.error;
        }
        mark_position(s, f.timestamp_ns);
        mark_torque(s, f.timestamp_ns);
        return DecodeStatus::Ok;
    }

private:
    JointConfig config_{};
    CountUnwrapper unwrap_;
};

// Simulator side: the reply a motor would send for a link-side state. The position wraps as the
// firmware's does; velocity and effort saturate at their ranges.
inline void encode_reply(const JointConfig& c, double link_q, double link_qd, double link_tau, CanFrame& f,
                         bool with_status = true, int temperature_c = 25, std::uint8_t error = 0) noexcept {
    const JointMapping& m = c.mapping;
    const Ranges& g = c.ranges;
    RawReply r;
    r.motor_id = c.motor_id;
    r.position = position_to_code(motor_position(m, link_q), g);
    r.velocity = static_cast<std::uint16_t>(value_to_code(motor_velocity(m, link_qd), g.v_min, g.v_max, kVelocityBits));
    r.effort = static_cast<std::uint16_t>(value_to_code(device_effort(m, c.effort, link_tau), g.t_min, g.t_max, kEffortBits));
    r.has_status = with_status;
    const int t = temperature_c + c.temperature_offset;
    r.temperature = static_cast<std::uint8_t>(t < 0 ? 0 : (t > 255 ? 255 : t));
    r.error = error;
    pack_reply(r, c.reply_can_id, c.extended_id, f);
}

}  // namespace jacobid::hal::mit
