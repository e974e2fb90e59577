// SPDX-License-Identifier: MIT
#pragma once
// What the device profiles produce: one joint's state per cycle in link-side SI units, the mapping from
// the motor/device side to the link side, the decode status codes and the decode counters.
//
// Conversions (documented once here, used by every profile):
//   link position  q   = direction * q_motor / N - position_offset      [rad]
//   link velocity  qd  = direction * qd_motor / N                       [rad/s]
//   link torque    tau = direction * tau_motor * N                      [N.m] (device reports torque)
//   link torque    tau = direction * Kt * I * N                         [N.m] (device reports current)
// with N = gear_ratio (motor turns per link turn, N > 1 for a reducer) and Kt the motor torque constant
// (N.m/A, on the motor side, for the current the device reports: q-axis current for FOC drives). The
// torque relation is the ideal gearbox (no friction or efficiency loss): identification estimates
// friction separately, so it must not be folded in here. When a device already reports output-side
// values (e.g. an AK80-9 actuator reports its output shaft), N is the external ratio, often 1.
#include <cmath>
#include <cstdint>
#include <limits>

namespace jacobid::hal {

constexpr double kTwoPi = 6.283185307179586476925286766559;

enum class DecodeStatus {
    Ok,
    NotMine,     // the frame does not belong to this joint/profile (not an error, not counted)
    Short,       // fewer data bytes than the profile's layout needs
    OutOfRange,  // a field is outside what the device can report or the configured plausibility limits
    UnknownId,   // no configured joint claims the frame (only from JointDecoderSet::dispatch)
    Malformed,   // remote or FD frame where a classic data frame is expected, or similar
};

inline const char* describe(DecodeStatus s) noexcept {
    switch (s) {
        case DecodeStatus::Ok: return "ok";
        case DecodeStatus::NotMine: return "frame belongs to another joint or profile";
        case DecodeStatus::Short: return "frame too short for the profile's layout";
        case DecodeStatus::OutOfRange: return "decoded value out of range (invalid field or beyond the plausibility limits)";
        case DecodeStatus::UnknownId: return "no configured joint claims this CAN id (or MIT motor id)";
        case DecodeStatus::Malformed: return "remote, FD or otherwise unexpected frame type for this profile";
    }
    return "unknown decode status";
}

enum class ConfigStatus {
    Ok,
    InvalidGearRatio,      // N must be finite and non-zero
    GearRatioOutOfRange,   // |N| within kMinGearRatio..kMaxGearRatio
    InvalidOffset,         // |position offset| within kMaxPositionOffset
    InvalidDirection,      // direction must be +1 or -1
    InvalidTorqueConstant, // Kt must be finite and > 0 where the device reports current
    InvalidLimits,         // plausibility limits must be > 0 (infinity disables)
    InvalidRange,          // MIT: min >= max or not finite
    InvalidCanId,          // id wider than its format
    InvalidNodeId,         // CANopen 1..127, ODrive 0..63
    InvalidScale,          // counts per revolution, rated current/torque, scale: finite and non-zero
    InvalidLayout,         // generic: width 0 or > 64, field beyond 64 bytes, ...
    TooManyJoints,
};

inline const char* describe(ConfigStatus s) noexcept {
    switch (s) {
        case ConfigStatus::Ok: return "ok";
        case ConfigStatus::InvalidGearRatio: return "gear ratio must be finite and non-zero";
        case ConfigStatus::GearRatioOutOfRange: return "gear ratio must be of magnitude 1e-06 to 1e+06 (motor turns per link turn)";
        case ConfigStatus::InvalidOffset: return "position offset must be a finite number within +-10000 (rad or m, link side)";
        case ConfigStatus::InvalidDirection: return "direction must be +1 or -1";
        case ConfigStatus::InvalidTorqueConstant: return "torque constant Kt must be finite and > 0 when the device reports current";
        case ConfigStatus::InvalidLimits: return "plausibility limits must be > 0 (infinity disables them)";
        case ConfigStatus::InvalidRange: return "range minimum must be below its maximum, both finite";
        case ConfigStatus::InvalidCanId: return "CAN id wider than its format (11 or 29 bits)";
        case ConfigStatus::InvalidNodeId: return "node id out of range (CANopen 1..127, ODrive 0..63)";
        case ConfigStatus::InvalidScale: return "scale factor (counts/rev, rated current/torque, scale) must be finite and non-zero";
        case ConfigStatus::InvalidLayout: return "signal layout invalid (bit width 1..64, field within 64 bytes)";
        case ConfigStatus::TooManyJoints: return "more joints than the decoder set holds";
    }
    return "unknown config status";
}

// Whether the device's effort field is a torque or a current (then Kt converts it).
enum class EffortKind : std::uint8_t { Torque, Current };

struct JointMapping {
    double gear_ratio = 1.0;       // N: motor (device) turns per link turn
    double direction = 1.0;        // +1, or -1 when the device counts against the joint convention
    double position_offset = 0.0;  // rad, link side, subtracted after the ratio (joint zero)
    double torque_constant = 0.0;  // Kt, N.m/A on the motor side; needed only with EffortKind::Current
    // Plausibility limits, link side; a decoded value beyond them is rejected as OutOfRange rather than
    // fed to the identification. Infinity (default) disables.
    double max_abs_velocity = std::numeric_limits<double>::infinity();  // rad/s
    double max_abs_torque = std::numeric_limits<double>::infinity();    // N.m
};

// Far beyond any reducer (harmonic drives ~160:1, lead screws in rad/m ~1e4) and any joint zero, and small
// enough that the conversions below cannot overflow a decoded value: a gear ratio of 1e308 was accepted and
// every frame read as out of range, an offset of 1e308 moved every position to -1e308 (issue 20).
constexpr double kMinGearRatio = 1e-6, kMaxGearRatio = 1e6;
constexpr double kMaxPositionOffset = 1e4;

inline ConfigStatus validate(const JointMapping& m, EffortKind effort) noexcept {
    if (!std::isfinite(m.gear_ratio) || m.gear_ratio == 0.0) return ConfigStatus::InvalidGearRatio;
    if (!(std::abs(m.gear_ratio) >= kMinGearRatio && std::abs(m.gear_ratio) <= kMaxGearRatio)) return ConfigStatus::GearRatioOutOfRange;
    if (m.direction != 1.0 && m.direction != -1.0) return ConfigStatus::InvalidDirection;
    if (!(std::abs(m.position_offset) <= kMaxPositionOffset)) return ConfigStatus::InvalidOffset;
    if (effort == EffortKind::Current && (!std::isfinite(m.torque_constant) || m.torque_constant <= 0.0))
        return ConfigStatus::InvalidTorqueConstant;
    if (!(m.max_abs_velocity > 0.0) || !(m.max_abs_torque > 0.0)) return ConfigStatus::InvalidLimits;
    return ConfigStatus::Ok;
}

// --- device (motor) side <-> link side ---
inline double link_position(const JointMapping& m, double motor_rad) noexcept {
    return m.direction * motor_rad / m.gear_ratio - m.position_offset;
}
inline double motor_position(const JointMapping& m, double link_rad) noexcept {
    return m.direction * (link_rad + m.position_offset) * m.gear_ratio;
}
inline double link_velocity(const JointMapping& m, double motor_rad_s) noexcept {
    return m.direction * motor_rad_s / m.gear_ratio;
}
inline double motor_velocity(const JointMapping& m, double link_rad_s) noexcept {
    return m.direction * link_rad_s * m.gear_ratio;
}
// Device effort (torque in N.m or current in A, motor side) to link torque.
inline double link_torque(const JointMapping& m, EffortKind kind, double effort) noexcept {
    const double motor_torque = kind == EffortKind::Current ? m.torque_constant * effort : effort;
    return m.direction * motor_torque * m.gear_ratio;
}
inline double device_effort(const JointMapping& m, EffortKind kind, double link_tau) noexcept {
    const double motor_torque = m.direction * link_tau / m.gear_ratio;
    return kind == EffortKind::Current ? motor_torque / m.torque_constant : motor_torque;
}

// One joint's state, updated by the decoders as frames arrive and aged once per cycle by begin_cycle().
struct JointState {
    static constexpr std::uint32_t kNever = std::numeric_limits<std::uint32_t>::max();

    double position = 0.0;  // rad, link side, multi-turn unwrapped
    double velocity = 0.0;  // rad/s, link side, as reported by the device (0 if it reports none)
    double torque = 0.0;    // N.m, link side
    std::int64_t position_time_ns = 0;  // receive timestamp of the frame that set position
    std::int64_t torque_time_ns = 0;    // receive timestamp of the frame that set torque
    std::uint32_t position_age = kNever;  // cycles since position was last updated (kNever: not yet)
    std::uint32_t torque_age = kNever;    // cycles since torque was last updated
    std::uint8_t device_error = 0;      // device fault code where the profile reports one (MIT byte 7)
    std::int16_t temperature_c = 0;     // where the profile reports one
    bool position_fresh = false;  // position updated during this cycle
    bool torque_fresh = false;    // torque updated during this cycle
    bool stale = true;            // position or torque older than the limit, or never seen: do not use
    bool decode_error = false;    // a frame for this joint was rejected during this cycle

    bool fresh() const noexcept { return position_fresh && torque_fresh; }
};

inline void update_stale(JointState& s, std::uint32_t max_age) noexcept {
    s.stale = s.position_age > max_age || s.torque_age > max_age;
}

// Call once per cycle before dispatching the cycle's frames: ages the values and clears the per-cycle
// flags. A value is stale once it has not been refreshed for more than `max_age` cycles (0: it must
// arrive every cycle).
inline void begin_cycle(JointState& s, std::uint32_t max_age) noexcept {
    if (s.position_age != JointState::kNever) ++s.position_age;
    if (s.torque_age != JointState::kNever) ++s.torque_age;
    s.position_fresh = s.torque_fresh = false;
    s.decode_error = false;
    update_stale(s, max_age);
}

// Used by the decoders when a frame sets a value; the decoder set then calls update_stale().
inline void mark_position(JointState& s, std::int64_t t_ns) noexcept {
    s.position_fresh = true;
    s.position_age = 0;
    s.position_time_ns = t_ns;
}
inline void mark_torque(JointState& s, std::int64_t t_ns) noexcept {
    s.torque_fresh = true;
    s.torque_age = 0;
    s.torque_time_ns = t_ns;
}

// Decode counters of a decoder set, monotonic since configure().
struct DecodeCounters {
    std::uint64_t frames = 0;            // frames offered to dispatch()
    std::uint64_t decoded = 0;           // frames decoded into a joint state
    std::uint64_t rejected_short = 0;
    std::uint64_t rejected_out_of_range = 0;
    std::uint64_t rejected_unknown_id = 0;
    std::uint64_t rejected_malformed = 0;
};

}  // namespace jacobid::hal
