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
//
// Command (the mini-cheetah's pack_cmd(), CubeMars "MIT mode"), sent on CAN id = motor id, 8 bytes,
// big-endian bit fields: position 16 bit, velocity 12, kp 12, kd 12, feed-forward torque 12, each a
// linear code over its range (kp over 0..kp_max, kd over 0..kd_max); the drive applies
// tau = kp (p_des - p) + kd (v_des - v) + t_ff. Byte layout: docs/profiles.md, "MIT mode".
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "jacobid/hal/profiles/profile_entry.hpp"

namespace jacobid::hal::mit {

constexpr unsigned kPositionBits = 16;
constexpr unsigned kVelocityBits = 12;
constexpr unsigned kEffortBits = 12;
constexpr unsigned kGainBits = 12;
constexpr std::uint8_t kCommandLength = 8;
constexpr std::uint8_t kShortReplyLength = 6;   // mini-cheetah: id, position, velocity, effort
constexpr std::uint8_t kStatusReplyLength = 8;  // AK / CubeMars: + temperature, error

struct Ranges {
    double p_min = -12.5, p_max = 12.5;  // rad
    double v_min = -50.0, v_max = 50.0;  // rad/s
    double t_min = -18.0, t_max = 18.0;  // N.m (or A with EffortKind::Current)
    double kp_max = 500.0;  // N.m/rad, command gains range over 0..kp_max (AK / CubeMars: 500)
    double kd_max = 5.0;    // N.m.s/rad, over 0..kd_max (AK / CubeMars: 5)
};
// Defaults of common actuators (manufacturer ranges of the MIT-mode scaling, output side).
constexpr Ranges kAk80_9{-12.5, 12.5, -50.0, 50.0, -18.0, 18.0};
constexpr Ranges kMiniCheetah{-12.5, 12.5, -65.0, 65.0, -18.0, 18.0};  // v/t: per-build firmware constants

inline ConfigStatus validate(const Ranges& r) noexcept {
    // The span hi - lo must be finite too: it scales every code (-1e308..1e308 would overflow it).
    auto ok = [](double lo, double hi) { return std::isfinite(lo) && std::isfinite(hi) && lo < hi && std::isfinite(hi - lo); };
    return ok(r.p_min, r.p_max) && ok(r.v_min, r.v_max) && ok(r.t_min, r.t_max) && ok(0.0, r.kp_max) && ok(0.0, r.kd_max)
               ? ConfigStatus::Ok
               : ConfigStatus::InvalidRange;
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
    std::uint8_t motor_id = 1;       // data[0] of this joint's replies, and the standard id of its commands
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

// Defaults of joint `index` (0-based), the same for jacobid-fw and sim-can (docs/firmware.md, "Profiles
// and resolution"): every motor replies on id 0 with data[0] = index + 1 (8-byte replies); +-12.5 rad,
// +-65 rad/s, +-30 N.m; gear ratio 4.
inline void apply_firmware_defaults(JointConfig& c, std::size_t index) noexcept {
    c.motor_id = static_cast<std::uint8_t>(index + 1);
    c.ranges.v_min = -65.0, c.ranges.v_max = 65.0;
    c.ranges.t_min = -30.0, c.ranges.t_max = 30.0;
    c.require_status = true;
    c.mapping.gear_ratio = 4.0;
}

// The profile's keys of a fw.yaml joint (Fields: yaml_section.hpp's interface).
template <typename Fields>
void read_config(Fields& s, JointConfig& c) {
    c.reply_can_id = static_cast<std::uint32_t>(s.integer("reply_id", static_cast<long>(c.reply_can_id), 0, kCanExtendedIdMask));
    c.extended_id = s.boolean("extended_id", c.extended_id);
    c.motor_id = static_cast<std::uint8_t>(s.integer("motor_id", c.motor_id, 0, 255));
    const auto p = s.range("position_range", {c.ranges.p_min, c.ranges.p_max});
    const auto v = s.range("velocity_range", {c.ranges.v_min, c.ranges.v_max});
    const auto t = s.range("effort_range", {c.ranges.t_min, c.ranges.t_max});
    c.ranges.p_min = p.first, c.ranges.p_max = p.second;
    c.ranges.v_min = v.first, c.ranges.v_max = v.second;
    c.ranges.t_min = t.first, c.ranges.t_max = t.second;
    c.effort = s.choice("effort", "torque", {"torque", "current"}) == "current" ? EffortKind::Current : EffortKind::Torque;
    c.require_status = s.boolean("require_status", c.require_status);
    c.mapping = read_mapping(s, c.mapping);
}

inline const char* config_key_of(const JointConfig&, ConfigStatus s) noexcept {
    if (const char* k = mapping_key_of(s)) return k;
    return s == ConfigStatus::InvalidCanId ? "reply_id" : s == ConfigStatus::InvalidRange ? "effort_range" : "profile";
}
// The firmware's position code wraps at 2^16 codes.
inline std::uint64_t unwrap_period(const JointConfig&) noexcept { return 1u << kPositionBits; }

// Joint side of the profile: claims this motor's replies, unwraps, scales and maps to the link side.
class JointDecoder : public JointDecoderBase<JointConfig, CountUnwrapper> {
public:
    // The one test of "is this frame mine" (docs/profiles.md): every caller goes through decode.
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
        double position = 0.0;
        const auto to_link = [&](std::int64_t code) {
            return link_position(m, g.p_min + static_cast<double>(code) * (g.p_max - g.p_min) / 65535.0);
        };
        if (!commit_position(static_cast<std::int64_t>(r.position), to_link, position)) return DecodeStatus::OutOfRange;
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

// --- commands (controller -> drive) ---

// The command fields exactly as on the wire.
struct RawCommand {
    std::uint16_t position = 0;  // 16 bit
    std::uint16_t velocity = 0;  // 12 bit
    std::uint16_t kp = 0;        // 12 bit
    std::uint16_t kd = 0;        // 12 bit
    std::uint16_t torque = 0;    // 12 bit
};

inline void pack_command(const RawCommand& r, std::uint8_t motor_id, CanFrame& f) noexcept {
    f = CanFrame{};
    f.id = motor_id;
    f.len = kCommandLength;
    auto* d = f.data.data();
    d[0] = static_cast<std::uint8_t>(r.position >> 8);
    d[1] = static_cast<std::uint8_t>(r.position & 0xFF);
    d[2] = static_cast<std::uint8_t>((r.velocity >> 4) & 0xFF);
    d[3] = static_cast<std::uint8_t>(((r.velocity & 0x0F) << 4) | ((r.kp >> 8) & 0x0F));
    d[4] = static_cast<std::uint8_t>(r.kp & 0xFF);
    d[5] = static_cast<std::uint8_t>((r.kd >> 4) & 0xFF);
    d[6] = static_cast<std::uint8_t>(((r.kd & 0x0F) << 4) | ((r.torque >> 8) & 0x0F));
    d[7] = static_cast<std::uint8_t>(r.torque & 0xFF);
}

// Drive side (sim-can): layout only, the id is the caller's business.
inline DecodeStatus unpack_command(const CanFrame& f, RawCommand& out) noexcept {
    if (f.remote() || f.fd() || f.error() || f.len > kCanMaxDataLength) return DecodeStatus::Malformed;
    if (f.len < kCommandLength) return DecodeStatus::Short;
    const auto* d = f.data.data();
    out.position = static_cast<std::uint16_t>((d[0] << 8) | d[1]);
    out.velocity = static_cast<std::uint16_t>((d[2] << 4) | (d[3] >> 4));
    out.kp = static_cast<std::uint16_t>(((d[3] & 0x0F) << 8) | d[4]);
    out.kd = static_cast<std::uint16_t>((d[5] << 4) | (d[6] >> 4));
    out.torque = static_cast<std::uint16_t>(((d[6] & 0x0F) << 8) | d[7]);
    return DecodeStatus::Ok;
}

// A link-side command as the drive's codes: every field saturates at its range (a setpoint beyond the
// position range is clamped, never wrapped: the drive would otherwise jump a turn). Torque mode sends
// kp = kd = 0, so the drive applies the feed-forward torque alone.
inline std::size_t encode_command(const JointConfig& c, const JointCommand& cmd, CanFrame* out) noexcept {
    const JointMapping& m = c.mapping;
    const Ranges& g = c.ranges;
    const bool torque_only = cmd.mode == CommandMode::Torque;
    RawCommand r;
    r.position = static_cast<std::uint16_t>(
        value_to_code(torque_only ? 0.5 * (g.p_min + g.p_max) : motor_position(m, cmd.position), g.p_min, g.p_max, kPositionBits));
    r.velocity = static_cast<std::uint16_t>(value_to_code(torque_only ? 0.0 : motor_velocity(m, cmd.velocity), g.v_min, g.v_max, kVelocityBits));
    r.kp = static_cast<std::uint16_t>(value_to_code(torque_only ? 0.0 : cmd.kp, 0.0, g.kp_max, kGainBits));
    r.kd = static_cast<std::uint16_t>(value_to_code(torque_only ? 0.0 : cmd.kd, 0.0, g.kd_max, kGainBits));
    r.torque = static_cast<std::uint16_t>(value_to_code(device_effort(m, c.effort, cmd.torque), g.t_min, g.t_max, kEffortBits));
    pack_command(r, c.motor_id, out[0]);
    return 1;
}

// The mode frames of the MIT protocol: seven 0xFF bytes, then FC (enter motor mode: the drive starts
// following commands), FD (exit: the drive goes limp) or FE (the current position becomes zero).
enum class ModeRequest : std::uint8_t { EnterMotorMode = 0xFC, ExitMotorMode = 0xFD, SetZeroPosition = 0xFE };
inline void encode_mode_request(const JointConfig& c, ModeRequest request, CanFrame& f) noexcept {
    f = CanFrame{};
    f.id = c.motor_id;
    f.len = kCommandLength;
    for (std::size_t i = 0; i < 7; ++i) f.data[i] = 0xFF;
    f.data[7] = static_cast<std::uint8_t>(request);
}

// Whether `f` is one of the mode frames above rather than a setpoint.
inline bool is_mode_request(const CanFrame& f) noexcept {
    if (f.len != kCommandLength || f.data[7] < 0xFC || f.data[7] > 0xFE) return false;
    for (std::size_t i = 0; i < 7; ++i) {
        if (f.data[i] != 0xFF) return false;
    }
    return true;
}

// Drive side (a simulated motor following commands): this motor's command frame as a link-side
// JointCommand; kp = kd = 0 reads as Torque mode. Mode frames are not setpoints (NotMine; is_mode_request).
inline DecodeStatus decode_command(const JointConfig& c, CommandMode /*drive_mode*/, const CanFrame& f, JointCommand& out) noexcept {
    if (f.extended() || f.id != c.motor_id || is_mode_request(f)) return DecodeStatus::NotMine;
    RawCommand r;
    if (const DecodeStatus st = unpack_command(f, r); st != DecodeStatus::Ok) return st;
    const JointMapping& m = c.mapping;
    const Ranges& g = c.ranges;
    out.mode = r.kp == 0 && r.kd == 0 ? CommandMode::Torque : CommandMode::Position;
    out.position = link_position(m, code_to_value(r.position, g.p_min, g.p_max, kPositionBits));
    out.velocity = link_velocity(m, code_to_value(r.velocity, g.v_min, g.v_max, kVelocityBits));
    out.torque = link_torque(m, c.effort, code_to_value(r.torque, g.t_min, g.t_max, kEffortBits));
    out.kp = code_to_value(r.kp, 0.0, g.kp_max, kGainBits);
    out.kd = code_to_value(r.kd, 0.0, g.kd_max, kGainBits);
    return DecodeStatus::Ok;
}

// The registry's drive side (profile_entry.hpp).
inline std::size_t encode_telemetry(const JointConfig& c, double q, double qd, double tau, CanFrame* out) noexcept {
    encode_reply(c, q, qd, tau, out[0], c.require_status);
    return 1;
}

// The registry entry (hal/profile_registry.hpp, docs/profiles.md).
struct Profile : ProfileEntry<JointConfig, JointDecoder, 1, true> {
    static constexpr const char* kName = "mit";
};

}  // namespace jacobid::hal::mit
