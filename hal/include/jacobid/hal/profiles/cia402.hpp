// SPDX-License-Identifier: MIT
#pragma once
// CiA 402 drive, actual values from a transmit PDO (CANopen, CiA 301 data types: little-endian).
//
//   0x6064 position actual value  INT32, position units (encoder increments unless a factor group is set)
//   0x6078 current actual value   INT16, per mille of the motor rated current 0x6075 (UNSIGNED32, mA)
//   0x6077 torque actual value    INT16, per mille of the motor rated torque 0x6076 (UNSIGNED32, mN.m)
// Default mapping (a common TPDO1 configuration): bytes 0..3 position, bytes 4..5 current or torque,
// COB-ID 0x180 + node id. Other mappings are configured with byte offsets and the COB-ID.
//
// Conversions: motor angle = 2 pi * counts / counts_per_revolution; current = per_mille / 1000 * rated
// current (A), then link torque = Kt * I * N; torque = per_mille / 1000 * rated torque (motor side,
// N.m), then link torque = tau * N (joint_state.hpp). The INT32 position wraps at 2^32 counts, or every
// position_modulus counts for a drive with a modulo position range (0x607B); it is unwrapped on counts.
//
// Commands go through a receive PDO (default RPDO1, COB-ID 0x200 + node id), mapped on the drive as
//   0x6040 controlword     UINT16, bytes 0..1
//   0x607A target position INT32, bytes 2..5 (cyclic synchronous position, mode 8), or
//   0x6071 target torque   INT16, bytes 2..3, per mille of 0x6076 (cyclic synchronous torque, mode 10)
// The controlword walks the drive through the CiA 402 state machine (DriveEnabler below, driven by the
// statusword 0x6041); the drive follows the target only in "operation enabled". Byte layout:
// docs/profiles.md, "CiA 402".
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "jacobid/hal/profiles/profile_entry.hpp"

namespace jacobid::hal::cia402 {

constexpr std::uint16_t kPositionActualValue = 0x6064;
constexpr std::uint16_t kTorqueActualValue = 0x6077;
constexpr std::uint16_t kCurrentActualValue = 0x6078;

// Default COB-ID of TPDO n (1..4) of a node (CiA 301 predefined connection set).
constexpr std::uint32_t tpdo_cob_id(unsigned pdo, std::uint8_t node) noexcept {
    return 0x180u + 0x100u * (pdo - 1u) + node;
}
// Default COB-ID of RPDO n (1..4) of a node.
constexpr std::uint32_t rpdo_cob_id(unsigned pdo, std::uint8_t node) noexcept {
    return 0x200u + 0x100u * (pdo - 1u) + node;
}

enum class EffortObject : std::uint16_t {
    None = 0,                         // position only
    CurrentActual = kCurrentActualValue,
    TorqueActual = kTorqueActualValue,
};

struct TpdoLayout {
    std::uint32_t cob_id = 0;        // 0: TPDO1 of the node (0x180 + node id)
    std::uint8_t position_byte = 0;  // offset of the INT32 0x6064 in the PDO
    EffortObject effort = EffortObject::CurrentActual;
    std::uint8_t effort_byte = 4;    // offset of the INT16 0x6078 / 0x6077
};

struct RawTpdo {
    std::int32_t position = 0;
    std::int16_t effort_per_mille = 0;  // meaningful when the layout has an effort object
};

// Layout only (no COB-ID check): frame type and length.
inline DecodeStatus unpack_tpdo(const TpdoLayout& l, const CanFrame& f, RawTpdo& out) noexcept {
    if (f.remote() || f.fd() || f.error() || f.extended() || f.len > kCanMaxDataLength) return DecodeStatus::Malformed;
    if (f.len < l.position_byte + 4u) return DecodeStatus::Short;
    if (l.effort != EffortObject::None && f.len < l.effort_byte + 2u) return DecodeStatus::Short;
    out.position = static_cast<std::int32_t>(sign_extend(load_uint(&f.data[l.position_byte], 4, ByteOrder::LittleEndian), 32));
    out.effort_per_mille = l.effort == EffortObject::None
                               ? std::int16_t{0}
                               : static_cast<std::int16_t>(sign_extend(load_uint(&f.data[l.effort_byte], 2, ByteOrder::LittleEndian), 16));
    return DecodeStatus::Ok;
}

// Length = end of the last mapped object; unmapped bytes are zero. A layout that does not fit a
// classic frame (see validate()) yields an empty frame rather than writing out of bounds.
inline void pack_tpdo(const TpdoLayout& l, std::uint32_t cob_id, const RawTpdo& r, CanFrame& f) noexcept {
    f = CanFrame{};
    f.id = cob_id;
    if (l.position_byte + 4u > kCanMaxDataLength || (l.effort != EffortObject::None && l.effort_byte + 2u > kCanMaxDataLength)) return;
    unsigned len = l.position_byte + 4u;
    store_uint(&f.data[l.position_byte], 4, ByteOrder::LittleEndian, static_cast<std::uint32_t>(r.position));
    if (l.effort != EffortObject::None) {
        store_uint(&f.data[l.effort_byte], 2, ByteOrder::LittleEndian, static_cast<std::uint16_t>(r.effort_per_mille));
        if (l.effort_byte + 2u > len) len = l.effort_byte + 2u;
    }
    f.len = static_cast<std::uint8_t>(len);
}

// Where the command objects sit in the RPDO; the target object follows the command's mode.
struct RpdoLayout {
    std::uint32_t cob_id = 0;           // 0: RPDO1 of the node (0x200 + node id)
    std::uint8_t controlword_byte = 0;  // offset of the UINT16 0x6040
    std::uint8_t target_byte = 2;       // offset of the INT32 0x607A or the INT16 0x6071
};

struct JointConfig {
    std::uint8_t node_id = 1;        // 1..127
    TpdoLayout layout{};
    RpdoLayout command{};
    double counts_per_revolution = 0.0;  // position units per motor revolution (required)
    std::uint64_t position_modulus = 1ull << 32;  // counts after which 0x6064 wraps
    double rated_current = 0.0;      // A (0x6075 / 1000), for CurrentActual
    double rated_torque = 0.0;       // N.m (0x6076 / 1000), for TorqueActual
    // |per mille| beyond this is rejected: no drive delivers 10x its rating, so such a value is a
    // mapping or transmission error.
    int max_abs_per_mille = 10000;
    JointMapping mapping{};

    std::uint32_t cob_id() const noexcept { return layout.cob_id != 0 ? layout.cob_id : tpdo_cob_id(1, node_id); }
    std::uint32_t command_cob_id() const noexcept { return command.cob_id != 0 ? command.cob_id : rpdo_cob_id(1, node_id); }
    EffortKind effort_kind() const noexcept {
        return layout.effort == EffortObject::CurrentActual ? EffortKind::Current : EffortKind::Torque;
    }
};

inline ConfigStatus validate(const JointConfig& c) noexcept {
    if (c.node_id < 1 || c.node_id > 127) return ConfigStatus::InvalidNodeId;
    if ((c.cob_id() & ~kCanStandardIdMask) != 0) return ConfigStatus::InvalidCanId;
    if (c.layout.position_byte + 4u > kCanMaxDataLength) return ConfigStatus::InvalidLayout;
    if (c.layout.effort != EffortObject::None && c.layout.effort_byte + 2u > kCanMaxDataLength) return ConfigStatus::InvalidLayout;
    if (!std::isfinite(c.counts_per_revolution) || c.counts_per_revolution == 0.0) return ConfigStatus::InvalidScale;
    if (c.position_modulus < 2 || c.position_modulus > (1ull << 32)) return ConfigStatus::InvalidScale;
    if (c.layout.effort == EffortObject::CurrentActual && !(std::isfinite(c.rated_current) && c.rated_current > 0.0))
        return ConfigStatus::InvalidScale;
    if (c.layout.effort == EffortObject::TorqueActual && !(std::isfinite(c.rated_torque) && c.rated_torque > 0.0))
        return ConfigStatus::InvalidScale;
    if (c.max_abs_per_mille <= 0) return ConfigStatus::InvalidLimits;
    if ((c.command_cob_id() & ~kCanStandardIdMask) != 0) return ConfigStatus::InvalidCanId;
    // The controlword and the (widest, INT32) target fit the frame and do not overlap.
    const unsigned cw = c.command.controlword_byte, target = c.command.target_byte;
    if (cw + 2u > kCanMaxDataLength || target + 4u > kCanMaxDataLength || (cw < target + 4u && target < cw + 2u))
        return ConfigStatus::InvalidLayout;
    return validate(c.mapping, c.layout.effort == EffortObject::None ? EffortKind::Torque : c.effort_kind());
}

// Defaults of joint `index` (0-based), the same for jacobid-fw and sim-can (docs/firmware.md): node
// index + 1, TPDO1, 2^16 counts per motor turn, torque actual value in per mille of 2 N.m; gear ratio 4.
inline void apply_firmware_defaults(JointConfig& c, std::size_t index) noexcept {
    c.node_id = static_cast<std::uint8_t>(index + 1);
    c.layout.effort = EffortObject::TorqueActual;
    c.counts_per_revolution = 65536.0;
    c.rated_torque = 2.0;
    c.mapping.gear_ratio = 4.0;
}

template <typename Fields>
void read_config(Fields& s, JointConfig& c) {
    c.node_id = static_cast<std::uint8_t>(s.integer("node_id", c.node_id, 1, 127));
    c.layout.cob_id = static_cast<std::uint32_t>(s.integer("cob_id", 0, 0, kCanStandardIdMask));
    c.counts_per_revolution = s.positive("counts_per_rev", c.counts_per_revolution);
    const auto effort = s.choice("effort", "torque", {"torque", "current", "none"});
    c.layout.effort = effort == "torque"    ? EffortObject::TorqueActual
                      : effort == "current" ? EffortObject::CurrentActual
                                            : EffortObject::None;
    c.rated_torque = s.number("rated_torque", c.rated_torque);
    c.rated_current = s.number("rated_current", c.rated_current);
    c.layout.position_byte = static_cast<std::uint8_t>(s.integer("position_byte", c.layout.position_byte, 0, 4));
    c.layout.effort_byte = static_cast<std::uint8_t>(s.integer("effort_byte", c.layout.effort_byte, 0, 6));
    c.mapping = read_mapping(s, c.mapping);
    if (c.layout.effort == EffortObject::CurrentActual && !(c.rated_current > 0.0))
        s.fail(s.node(), "rated_current", "required (> 0 A) with effort: current");
    if (c.layout.effort == EffortObject::TorqueActual && !(c.rated_torque > 0.0)) s.fail("rated_torque", "must be > 0 N.m with effort: torque");
    if (c.layout.effort == EffortObject::CurrentActual && !s.has("torque_constant"))
        s.fail(s.node(), "torque_constant", "required (N.m/A) with effort: current");
}

inline const char* config_key_of(const JointConfig&, ConfigStatus s) noexcept {
    if (const char* k = mapping_key_of(s)) return k;
    switch (s) {
        case ConfigStatus::InvalidCanId: return "cob_id";
        case ConfigStatus::InvalidNodeId: return "node_id";
        case ConfigStatus::InvalidScale: return "counts_per_rev";
        case ConfigStatus::InvalidLayout: return "effort_byte";
        default: return "profile";
    }
}

// 0x6064 wraps at 2^32 counts, or at the modulo range.
inline std::uint64_t unwrap_period(const JointConfig& c) noexcept { return c.position_modulus; }

class JointDecoder : public JointDecoderBase<JointConfig, CountUnwrapper> {
public:
    // The one test of "is this frame mine" (docs/profiles.md): every caller goes through decode.
    DecodeStatus decode(const CanFrame& f, JointState& s) noexcept {
        if (f.id != config_.cob_id() || f.extended()) return DecodeStatus::NotMine;
        RawTpdo r;
        if (const DecodeStatus st = unpack_tpdo(config_.layout, f, r); st != DecodeStatus::Ok) return st;
        const JointMapping& m = config_.mapping;
        const bool has_effort = config_.layout.effort != EffortObject::None;
        double tau = 0.0;
        if (has_effort) {
            if (std::abs(static_cast<int>(r.effort_per_mille)) > config_.max_abs_per_mille) return DecodeStatus::OutOfRange;
            const double rated = config_.effort_kind() == EffortKind::Current ? config_.rated_current : config_.rated_torque;
            tau = link_torque(m, config_.effort_kind(), static_cast<double>(r.effort_per_mille) / 1000.0 * rated);
            if (!plausible(tau, m.max_abs_torque)) return DecodeStatus::OutOfRange;
        }
        // A modulo range reports 0..modulus-1: reading the field as signed would put the first sample a
        // period off, so sign extension is only right for the full INT32 range.
        const std::int64_t raw = config_.position_modulus == (1ull << 32)
                                     ? static_cast<std::int64_t>(r.position)
                                     : static_cast<std::int64_t>(static_cast<std::uint32_t>(r.position));
        if (config_.position_modulus != (1ull << 32) && static_cast<std::uint64_t>(raw) >= config_.position_modulus)
            return DecodeStatus::OutOfRange;
        double position = 0.0;
        const auto to_link = [&](std::int64_t counts) {
            return link_position(m, kTwoPi * static_cast<double>(counts) / config_.counts_per_revolution);
        };
        if (!commit_position(raw, to_link, position)) return DecodeStatus::OutOfRange;
        s.position = position;
        mark_position(s, f.timestamp_ns);
        if (has_effort) {
            s.torque = tau;
            mark_torque(s, f.timestamp_ns);
        }
        return DecodeStatus::Ok;
    }
};

// Simulator side: the TPDO a drive would send for a link-side state.
inline void encode_tpdo(const JointConfig& c, double link_q, double link_tau, CanFrame& f) noexcept {
    const double counts = std::round(motor_position(c.mapping, link_q) / kTwoPi * c.counts_per_revolution);
    RawTpdo r;
    // Wrap to the device's range the way a drive's counter does (modulo 2^32 or the modulo range).
    const double m = static_cast<double>(c.position_modulus);
    double w = counts - m * std::floor(counts / m);
    if (c.position_modulus == (1ull << 32) && w >= 2147483648.0) w -= m;
    r.position = c.position_modulus == (1ull << 32) ? static_cast<std::int32_t>(w)
                                                    : static_cast<std::int32_t>(static_cast<std::uint32_t>(w));
    if (c.layout.effort != EffortObject::None) {
        const double rated = c.effort_kind() == EffortKind::Current ? c.rated_current : c.rated_torque;
        double pm = std::round(device_effort(c.mapping, c.effort_kind(), link_tau) / rated * 1000.0);
        pm = pm > 32767.0 ? 32767.0 : (pm < -32768.0 ? -32768.0 : pm);
        r.effort_per_mille = static_cast<std::int16_t>(pm);
    }
    pack_tpdo(c.layout, c.cob_id(), r, f);
}

// --- commands (controller -> drive) ---

// Controlword commands of the CiA 402 state machine (bits 0..3 and 7 of 0x6040).
constexpr std::uint16_t kDisableVoltage = 0x00;
constexpr std::uint16_t kShutdown = 0x06;
constexpr std::uint16_t kSwitchOn = 0x07;
constexpr std::uint16_t kEnableOperation = 0x0F;
constexpr std::uint16_t kFaultReset = 0x80;  // acts on the rising edge of bit 7

enum class DriveState : std::uint8_t {
    NotReadyToSwitchOn,
    SwitchOnDisabled,
    ReadyToSwitchOn,
    SwitchedOn,
    OperationEnabled,
    QuickStopActive,
    FaultReactionActive,
    Fault,
    Unknown,  // a statusword no state matches (not a CiA 402 drive, or a corrupted frame)
};

// The state a statusword reports (CiA 402: bits 0..3, 5 and 6).
constexpr DriveState drive_state(std::uint16_t statusword) noexcept {
    switch (statusword & 0x4Fu) {
        case 0x00: return DriveState::NotReadyToSwitchOn;
        case 0x40: return DriveState::SwitchOnDisabled;
        case 0x0F: return DriveState::FaultReactionActive;
        case 0x08: return DriveState::Fault;
        default: break;
    }
    switch (statusword & 0x6Fu) {
        case 0x21: return DriveState::ReadyToSwitchOn;
        case 0x23: return DriveState::SwitchedOn;
        case 0x27: return DriveState::OperationEnabled;
        case 0x07: return DriveState::QuickStopActive;
        default: return DriveState::Unknown;
    }
}

// The enabling sequence, one controlword per statusword read: switch on disabled -> shutdown (0x06) ->
// switch on (0x07) -> enable operation (0x0F); a fault is reset with a rising edge of bit 7 (0x00, then
// 0x80); disabling sends shutdown (the drive goes to "ready to switch on", power stage off). State: only
// the last controlword sent (for the fault-reset edge).
class DriveEnabler {
public:
    std::uint16_t next(std::uint16_t statusword, bool enable) noexcept {
        last_ = enable ? towards_operation(drive_state(statusword)) : kShutdown;
        return last_;
    }
    std::uint16_t last_controlword() const noexcept { return last_; }

private:
    std::uint16_t towards_operation(DriveState s) const noexcept {
        switch (s) {
            case DriveState::SwitchOnDisabled: return kShutdown;
            case DriveState::ReadyToSwitchOn: return kSwitchOn;
            case DriveState::SwitchedOn:
            case DriveState::OperationEnabled: return kEnableOperation;
            case DriveState::Fault: return last_ == kFaultReset ? kDisableVoltage : kFaultReset;
            default: return kDisableVoltage;  // not ready, fault reaction, quick stop, unknown: wait
        }
    }
    std::uint16_t last_ = kDisableVoltage;
};

// The RPDO fields exactly as on the wire.
struct RawRpdo {
    std::uint16_t controlword = 0;
    CommandMode mode = CommandMode::Position;
    std::int32_t target_position = 0;      // counts (0x607A), Position mode
    std::int16_t target_torque_per_mille = 0;  // of 0x6076 (0x6071), Torque mode
};

// Length = end of the last mapped object; unmapped bytes are zero. A layout validate() refuses yields
// an empty frame rather than writing out of bounds.
inline void pack_rpdo(const RpdoLayout& l, std::uint32_t cob_id, const RawRpdo& r, CanFrame& f) noexcept {
    f = CanFrame{};
    f.id = cob_id;
    const bool position = r.mode == CommandMode::Position;
    const unsigned target_size = position ? 4u : 2u;
    if (l.controlword_byte + 2u > kCanMaxDataLength || l.target_byte + target_size > kCanMaxDataLength) return;
    store_uint(&f.data[l.controlword_byte], 2, ByteOrder::LittleEndian, r.controlword);
    if (position) store_uint(&f.data[l.target_byte], 4, ByteOrder::LittleEndian, static_cast<std::uint32_t>(r.target_position));
    else store_uint(&f.data[l.target_byte], 2, ByteOrder::LittleEndian, static_cast<std::uint16_t>(r.target_torque_per_mille));
    const unsigned end = l.target_byte + target_size > l.controlword_byte + 2u ? l.target_byte + target_size : l.controlword_byte + 2u;
    f.len = static_cast<std::uint8_t>(end);
}

// Drive side (sim-can): the mode is the drive's (0x6060), so the caller says which target is mapped.
inline DecodeStatus unpack_rpdo(const RpdoLayout& l, CommandMode mode, const CanFrame& f, RawRpdo& out) noexcept {
    if (f.remote() || f.fd() || f.error() || f.extended() || f.len > kCanMaxDataLength) return DecodeStatus::Malformed;
    const unsigned target_size = mode == CommandMode::Position ? 4u : 2u;
    if (f.len < l.controlword_byte + 2u || f.len < l.target_byte + target_size) return DecodeStatus::Short;
    out.mode = mode;
    out.controlword = static_cast<std::uint16_t>(load_uint(&f.data[l.controlword_byte], 2, ByteOrder::LittleEndian));
    const std::uint64_t raw = load_uint(&f.data[l.target_byte], target_size, ByteOrder::LittleEndian);
    if (mode == CommandMode::Position) out.target_position = static_cast<std::int32_t>(sign_extend(raw, 32));
    else out.target_torque_per_mille = static_cast<std::int16_t>(sign_extend(raw, 16));
    return DecodeStatus::Ok;
}

// Whether the config can express a command of this mode: a torque target needs the rated torque.
inline ConfigStatus validate_command(const JointConfig& c, CommandMode mode) noexcept {
    if (mode == CommandMode::Torque && !(std::isfinite(c.rated_torque) && c.rated_torque > 0.0)) return ConfigStatus::InvalidScale;
    return ConfigStatus::Ok;
}

// Link-side command -> RPDO with the given controlword (DriveEnabler::next). The target position is
// wrapped to the drive's range like its own counter; the torque saturates at INT16 per mille (and is 0
// when validate_command refuses the mode). CiA 402 has no velocity or torque feed-forward in CSP
// through this RPDO: they are not sent.
inline void encode_command(const JointConfig& c, std::uint16_t controlword, const JointCommand& cmd, CanFrame& f) noexcept {
    RawRpdo r;
    r.controlword = controlword;
    r.mode = cmd.mode;
    if (cmd.mode == CommandMode::Position) {
        const double counts = std::round(motor_position(c.mapping, cmd.position) / kTwoPi * c.counts_per_revolution);
        const double m = static_cast<double>(c.position_modulus);
        double w = std::isfinite(counts) ? counts - m * std::floor(counts / m) : 0.0;
        if (c.position_modulus == (1ull << 32) && w >= 2147483648.0) w -= m;
        r.target_position = c.position_modulus == (1ull << 32) ? static_cast<std::int32_t>(w)
                                                               : static_cast<std::int32_t>(static_cast<std::uint32_t>(w));
    } else if (validate_command(c, CommandMode::Torque) == ConfigStatus::Ok) {
        double pm = std::round(device_effort(c.mapping, EffortKind::Torque, cmd.torque) / c.rated_torque * 1000.0);
        pm = !(pm == pm) ? 0.0 : pm > 32767.0 ? 32767.0 : (pm < -32768.0 ? -32768.0 : pm);
        r.target_torque_per_mille = static_cast<std::int16_t>(pm);
    }
    pack_rpdo(c.command, c.command_cob_id(), r, f);
}

// Drive side (a simulated drive following commands): this node's RPDO as a link-side JointCommand. The
// drive's mode of operation (0x6060) says which target is mapped; the controlword is unpack_rpdo's.
inline DecodeStatus decode_command(const JointConfig& c, CommandMode drive_mode, const CanFrame& f, JointCommand& out) noexcept {
    if (f.extended() || f.id != c.command_cob_id()) return DecodeStatus::NotMine;
    RawRpdo r;
    if (const DecodeStatus st = unpack_rpdo(c.command, drive_mode, f, r); st != DecodeStatus::Ok) return st;
    out.mode = drive_mode;
    if (drive_mode == CommandMode::Torque) {
        if (validate_command(c, CommandMode::Torque) != ConfigStatus::Ok) return DecodeStatus::OutOfRange;
        out.torque = link_torque(c.mapping, EffortKind::Torque, static_cast<double>(r.target_torque_per_mille) / 1000.0 * c.rated_torque);
        return DecodeStatus::Ok;
    }
    // As 0x6064: signed over the full INT32 range, unsigned within a modulo range.
    const double counts = c.position_modulus == (1ull << 32) ? static_cast<double>(r.target_position)
                                                             : static_cast<double>(static_cast<std::uint32_t>(r.target_position));
    out.position = link_position(c.mapping, kTwoPi * counts / c.counts_per_revolution);
    return DecodeStatus::Ok;
}

// Registry functions (profile_entry.hpp). The registry's command is "operation enabled" (0x0F): the
// frame a playback sends once DriveEnabler has brought the drive there.
inline std::size_t encode_telemetry(const JointConfig& c, double q, double /*qd*/, double tau, CanFrame* out) noexcept {
    encode_tpdo(c, q, tau, out[0]);
    return 1;
}
inline std::size_t encode_command(const JointConfig& c, const JointCommand& cmd, CanFrame* out) noexcept {
    encode_command(c, kEnableOperation, cmd, out[0]);
    return 1;
}

// The registry entry (hal/profile_registry.hpp, docs/profiles.md).
struct Profile : ProfileEntry<JointConfig, JointDecoder, 1, true> {
    static constexpr const char* kName = "cia402";
};

}  // namespace jacobid::hal::cia402
