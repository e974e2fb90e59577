// SPDX-License-Identifier: MIT
#pragma once
// Generic signal profile, for devices without a dedicated profile: each quantity is one bit field of
// one CAN frame, described like a DBC signal but simpler.
//
// Layout: the field starts at `byte_offset` and spans ceil((bit_shift + bit_width) / 8) bytes, read as
// one integer in `order`; the value is (integer >> bit_shift) & (2^bit_width - 1), sign-extended when
// `is_signed`. bit_shift = 0 gives the common byte-aligned fields; a non-zero shift reaches packed
// fields (e.g. the MIT velocity: bytes 3..4 big-endian, shift 4, width 12).
// Physical value = raw * scale + offset. For the position that is the device angle in rad (motor side,
// before the gear ratio); for the effort a torque in N.m or a current in A (EffortKind).
// The position field wraps at 2^bit_width counts; it is unwrapped on counts when unwrap_position is set.
//
// Commands are laid out the same way (CommandLayout): the user writes one signal per setpoint (position,
// velocity, torque), each in a frame of its own id or sharing one; encode_command fills those frames.
// Example and byte layout: docs/profiles.md, "Generic".
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "jacobid/hal/profiles/profile_entry.hpp"

namespace jacobid::hal::generic {

struct Signal {
    std::uint32_t can_id = 0;
    bool extended_id = false;
    std::uint8_t byte_offset = 0;
    std::uint8_t bit_width = 16;  // 1..64
    std::uint8_t bit_shift = 0;   // 0..7
    bool is_signed = true;
    ByteOrder order = ByteOrder::LittleEndian;
    double scale = 1.0;
    double offset = 0.0;
    // Optional validity range of the raw value (e.g. a sensor that marks "invalid" with 0x8000).
    bool check_raw_range = false;
    std::int64_t raw_min = 0;
    std::int64_t raw_max = 0;

    std::size_t byte_count() const noexcept { return (static_cast<std::size_t>(bit_shift) + bit_width + 7u) / 8u; }
};

inline ConfigStatus validate(const Signal& s) noexcept {
    if ((s.can_id & ~(s.extended_id ? kCanExtendedIdMask : kCanStandardIdMask)) != 0) return ConfigStatus::InvalidCanId;
    if (s.bit_width < 1 || s.bit_width > 64 || s.bit_shift > 7 || s.byte_count() > 8) return ConfigStatus::InvalidLayout;
    if (s.byte_offset + s.byte_count() > kCanFdMaxDataLength) return ConfigStatus::InvalidLayout;
    if (!std::isfinite(s.scale) || s.scale == 0.0 || !std::isfinite(s.offset)) return ConfigStatus::InvalidScale;
    if (s.check_raw_range && s.raw_min > s.raw_max) return ConfigStatus::InvalidRange;
    return ConfigStatus::Ok;
}

inline bool is_signal_frame(const Signal& s, const CanFrame& f) noexcept {
    return f.id == s.can_id && f.extended() == s.extended_id;
}

// Raw value of the field (id not checked). Short when the frame ends before the field.
inline DecodeStatus extract_raw(const Signal& s, const CanFrame& f, std::int64_t& raw) noexcept {
    if (f.remote() || f.error() || f.len > (f.fd() ? kCanFdMaxDataLength : kCanMaxDataLength)) return DecodeStatus::Malformed;
    if (f.len < s.byte_offset + s.byte_count()) return DecodeStatus::Short;
    const std::uint64_t word = load_uint(&f.data[s.byte_offset], s.byte_count(), s.order) >> s.bit_shift;
    raw = s.is_signed ? sign_extend(word, s.bit_width) : static_cast<std::int64_t>(word & low_bits_mask(s.bit_width));
    if (s.check_raw_range && (raw < s.raw_min || raw > s.raw_max)) return DecodeStatus::OutOfRange;
    return DecodeStatus::Ok;
}

// Writes the field, leaving the other bits of its bytes as they are (several signals can share a
// frame). Grows f.len to cover the field.
inline void insert_raw(const Signal& s, std::int64_t raw, CanFrame& f) noexcept {
    if (s.byte_count() == 0 || s.byte_count() > 8 || s.byte_offset + s.byte_count() > kCanFdMaxDataLength) return;
    std::uint8_t* p = &f.data[s.byte_offset];
    const std::uint64_t field_mask = low_bits_mask(s.bit_width) << s.bit_shift;
    std::uint64_t word = load_uint(p, s.byte_count(), s.order);
    word = (word & ~field_mask) | ((static_cast<std::uint64_t>(raw) << s.bit_shift) & field_mask);
    store_uint(p, s.byte_count(), s.order, word);
    const auto end = static_cast<std::uint8_t>(s.byte_offset + s.byte_count());
    if (f.len < end) f.len = end;
}

inline double to_physical(const Signal& s, std::int64_t raw) noexcept { return static_cast<double>(raw) * s.scale + s.offset; }

// Nearest raw value, saturated to what the field can hold.
inline std::int64_t to_raw(const Signal& s, double physical) noexcept {
    const double r = std::round((physical - s.offset) / s.scale);
    const unsigned w = s.bit_width;
    const double lo = s.is_signed ? -std::ldexp(1.0, static_cast<int>(w) - 1) : 0.0;
    const double hi = s.is_signed ? std::ldexp(1.0, static_cast<int>(w) - 1) - 1.0 : std::ldexp(1.0, static_cast<int>(w)) - 1.0;
    if (!(r >= lo)) return static_cast<std::int64_t>(lo);  // also NaN
    if (r >= hi) return w >= 63 ? INT64_MAX : static_cast<std::int64_t>(hi);
    return static_cast<std::int64_t>(r);
}

// The command frames' signals (device side, like the telemetry's: rad, rad/s, N.m or A).
struct CommandLayout {
    bool has_position = false;
    Signal position{};
    bool has_velocity = false;
    Signal velocity{};
    bool has_torque = false;
    Signal torque{};  // in the joint's effort_kind units
};

struct JointConfig {
    Signal position{};
    bool unwrap_position = true;  // the field wraps at 2^bit_width counts (needs bit_width <= 32)
    bool has_velocity = false;
    Signal velocity{};            // device rad/s
    bool has_effort = true;
    Signal effort{};              // device N.m or A
    EffortKind effort_kind = EffortKind::Torque;
    JointMapping mapping{};
    CommandLayout command{};  // nothing by default: the joint is only read
};

inline ConfigStatus validate(const JointConfig& c) noexcept {
    for (const Signal* s : {&c.position, c.has_velocity ? &c.velocity : nullptr, c.has_effort ? &c.effort : nullptr}) {
        if (s == nullptr) continue;
        if (const ConfigStatus st = validate(*s); st != ConfigStatus::Ok) return st;
    }
    const CommandLayout& k = c.command;
    for (const Signal* s : {k.has_position ? &k.position : nullptr, k.has_velocity ? &k.velocity : nullptr, k.has_torque ? &k.torque : nullptr}) {
        if (s == nullptr) continue;
        if (const ConfigStatus st = validate(*s); st != ConfigStatus::Ok) return st;
    }
    if (c.unwrap_position && c.position.bit_width > 32) return ConfigStatus::InvalidLayout;
    return validate(c.mapping, c.has_effort ? c.effort_kind : EffortKind::Torque);
}

// The position field wraps at 2^bit_width counts when it is unwrapped (0: no unwrapping).
inline std::uint64_t unwrap_period(const JointConfig& c) noexcept { return c.unwrap_position ? (1ull << c.position.bit_width) : 0; }

class JointDecoder : public JointDecoderBase<JointConfig, CountUnwrapper> {
public:
    // The one test of "is this frame mine" (docs/profiles.md): every caller goes through decode.
    // Position, velocity and effort may share a frame or come in separate ones; every field the frame
    // carries is checked before any is stored, so a rejected frame changes nothing.
    DecodeStatus decode(const CanFrame& f, JointState& s) noexcept {
        const JointConfig& c = config_;
        const bool pos = is_signal_frame(c.position, f);
        const bool vel = c.has_velocity && is_signal_frame(c.velocity, f);
        const bool eff = c.has_effort && is_signal_frame(c.effort, f);
        if (!pos && !vel && !eff) return DecodeStatus::NotMine;
        const JointMapping& m = c.mapping;
        std::int64_t raw_p = 0, raw_v = 0, raw_e = 0;
        double v = 0.0, tau = 0.0;
        if (pos) {
            if (const DecodeStatus st = extract_raw(c.position, f, raw_p); st != DecodeStatus::Ok) return st;
        }
        if (vel) {
            if (const DecodeStatus st = extract_raw(c.velocity, f, raw_v); st != DecodeStatus::Ok) return st;
            v = link_velocity(m, to_physical(c.velocity, raw_v));
            if (!plausible(v, m.max_abs_velocity)) return DecodeStatus::OutOfRange;
        }
        if (eff) {
            if (const DecodeStatus st = extract_raw(c.effort, f, raw_e); st != DecodeStatus::Ok) return st;
            tau = link_torque(m, c.effort_kind, to_physical(c.effort, raw_e));
            if (!plausible(tau, m.max_abs_torque)) return DecodeStatus::OutOfRange;
        }
        if (pos) {
            double position = 0.0;
            const auto to_link = [&](std::int64_t counts) { return link_position(m, to_physical(c.position, counts)); };
            if (!commit_position(raw_p, to_link, position)) return DecodeStatus::OutOfRange;
            s.position = position;
            mark_position(s, f.timestamp_ns);
        }
        if (vel) s.velocity = v;
        if (eff) {
            s.torque = tau;
            mark_torque(s, f.timestamp_ns);
        }
        return DecodeStatus::Ok;
    }
};

// Simulator side: writes the fields of `f` that belong to its id (position, velocity, effort), wrapping
// the position to the field width as the device would. Call with a zeroed frame whose id and
// flags are set, once per CAN id the joint uses.
inline void encode_fields(const JointConfig& c, double link_q, double link_qd, double link_tau, CanFrame& f) noexcept {
    const JointMapping& m = c.mapping;
    if (is_signal_frame(c.position, f)) {
        const Signal& s = c.position;
        const double r = std::round((motor_position(m, link_q) - s.offset) / s.scale);
        // Wrap modulo 2^width (insert_raw keeps the low bits), saturate only when not wrapping.
        insert_raw(s, c.unwrap_position ? static_cast<std::int64_t>(r) : to_raw(s, motor_position(m, link_q)), f);
    }
    if (c.has_velocity && is_signal_frame(c.velocity, f)) insert_raw(c.velocity, to_raw(c.velocity, motor_velocity(m, link_qd)), f);
    if (c.has_effort && is_signal_frame(c.effort, f))
        insert_raw(c.effort, to_raw(c.effort, device_effort(m, c.effort_kind, link_tau)), f);
}

// The frame of `s`'s id among out[0..count): found, or started (zeroed, id and format set) at the end.
inline CanFrame& frame_of(const Signal& s, CanFrame* out, std::size_t& count) noexcept {
    for (std::size_t i = 0; i < count; ++i) {
        if (is_signal_frame(s, out[i])) return out[i];
    }
    CanFrame& f = out[count++];
    f = CanFrame{};
    f.id = s.can_id;
    f.flags = s.extended_id ? kCanExtended : 0;
    return f;
}

// A field beyond byte 8 needs a CAN FD frame, of the next length FD can carry.
inline void fit_length(CanFrame& f) noexcept {
    if (f.len <= kCanMaxDataLength) return;
    f.flags |= kCanFd;
    while (!is_valid_fd_length(f.len)) ++f.len;
}

// Simulator side, every frame of the joint for one sample (one per distinct id: at most 3).
inline std::size_t encode_telemetry(const JointConfig& c, double link_q, double link_qd, double link_tau, CanFrame* out) noexcept {
    std::size_t n = 0;
    for (const Signal* s : {&c.position, c.has_velocity ? &c.velocity : nullptr, c.has_effort ? &c.effort : nullptr}) {
        if (s != nullptr) frame_of(*s, out, n);
    }
    for (std::size_t i = 0; i < n; ++i) {
        encode_fields(c, link_q, link_qd, link_tau, out[i]);
        fit_length(out[i]);
    }
    return n;
}

// Link-side command -> the user's command frames (one per distinct id, at most 3). Position mode writes
// every setpoint the layout has; Torque mode only the torque. Values saturate at their field (no wrap:
// a wrapped setpoint would send the joint a turn away).
inline std::size_t encode_command(const JointConfig& c, const JointCommand& cmd, CanFrame* out) noexcept {
    const CommandLayout& k = c.command;
    const JointMapping& m = c.mapping;
    const bool position_mode = cmd.mode == CommandMode::Position;
    std::size_t n = 0;
    if (position_mode && k.has_position) insert_raw(k.position, to_raw(k.position, motor_position(m, cmd.position)), frame_of(k.position, out, n));
    if (position_mode && k.has_velocity) insert_raw(k.velocity, to_raw(k.velocity, motor_velocity(m, cmd.velocity)), frame_of(k.velocity, out, n));
    if (k.has_torque) insert_raw(k.torque, to_raw(k.torque, device_effort(m, c.effort_kind, cmd.torque)), frame_of(k.torque, out, n));
    for (std::size_t i = 0; i < n; ++i) fit_length(out[i]);
    return n;
}

// Drive side (a simulated device following commands): the setpoints this frame carries, link side; the
// other fields keep their values (a layout may spread a command over several frames). Every field is
// checked before any is written.
inline DecodeStatus decode_command(const JointConfig& c, CommandMode drive_mode, const CanFrame& f, JointCommand& out) noexcept {
    const CommandLayout& k = c.command;
    const bool pos = k.has_position && is_signal_frame(k.position, f);
    const bool vel = k.has_velocity && is_signal_frame(k.velocity, f);
    const bool tau = k.has_torque && is_signal_frame(k.torque, f);
    if (!pos && !vel && !tau) return DecodeStatus::NotMine;
    std::int64_t raw_p = 0, raw_v = 0, raw_t = 0;
    if (pos) {
        if (const DecodeStatus st = extract_raw(k.position, f, raw_p); st != DecodeStatus::Ok) return st;
    }
    if (vel) {
        if (const DecodeStatus st = extract_raw(k.velocity, f, raw_v); st != DecodeStatus::Ok) return st;
    }
    if (tau) {
        if (const DecodeStatus st = extract_raw(k.torque, f, raw_t); st != DecodeStatus::Ok) return st;
    }
    const JointMapping& m = c.mapping;
    out.mode = drive_mode;
    if (pos) out.position = link_position(m, to_physical(k.position, raw_p));
    if (vel) out.velocity = link_velocity(m, to_physical(k.velocity, raw_v));
    if (tau) out.torque = link_torque(m, c.effort_kind, to_physical(k.torque, raw_t));
    return DecodeStatus::Ok;
}

// The registry entry (hal/profile_registry.hpp, docs/profiles.md). Not offered in fw.yaml: a signal
// layout is written in C++ rather than guessed from defaults.
struct Profile : ProfileEntry<JointConfig, JointDecoder, 3, false> {
    static constexpr const char* kName = "generic";
};

}  // namespace jacobid::hal::generic
