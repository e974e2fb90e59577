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
#include <cmath>
#include <cstdint>

#include "jacobid/hal/byte_codec.hpp"
#include "jacobid/hal/can_frame.hpp"
#include "jacobid/hal/joint_state.hpp"
#include "jacobid/hal/profiles/plausibility.hpp"
#include "jacobid/hal/unwrap.hpp"

namespace jacobid::hal::cia402 {

constexpr std::uint16_t kPositionActualValue = 0x6064;
constexpr std::uint16_t kTorqueActualValue = 0x6077;
constexpr std::uint16_t kCurrentActualValue = 0x6078;

// Default COB-ID of TPDO n (1..4) of a node (CiA 301 predefined connection set).
constexpr std::uint32_t tpdo_cob_id(unsigned pdo, std::uint8_t node) noexcept {
    return 0x180u + 0x100u * (pdo - 1u) + node;
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

struct JointConfig {
    std::uint8_t node_id = 1;        // 1..127
    TpdoLayout layout{};
    double counts_per_revolution = 0.0;  // position units per motor revolution (required)
    std::uint64_t position_modulus = 1ull << 32;  // counts after which 0x6064 wraps
    double rated_current = 0.0;      // A (0x6075 / 1000), for CurrentActual
    double rated_torque = 0.0;       // N.m (0x6076 / 1000), for TorqueActual
    // |per mille| beyond this is rejected: no drive delivers 10x its rating, so such a value is a
    // mapping or transmission error.
    int max_abs_per_mille = 10000;
    JointMapping mapping{};

    std::uint32_t cob_id() const noexcept { return layout.cob_id != 0 ? layout.cob_id : tpdo_cob_id(1, node_id); }
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
    return validate(c.mapping, c.layout.effort == EffortObject::None ? EffortKind::Torque : c.effort_kind());
}

class JointDecoder {
public:
    ConfigStatus configure(const JointConfig& c) noexcept {
        const ConfigStatus s = validate(c);
        if (s == ConfigStatus::Ok) {
            config_ = c;
            unwrap_.set_modulus(c.position_modulus);
        }
        return s;
    }
    const JointConfig& config() const noexcept { return config_; }
    void reset() noexcept { unwrap_.reset(); }

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
        CountUnwrapper next = unwrap_;  // moved only by a frame that passes every check
        const double position = link_position(m, kTwoPi * static_cast<double>(next.update(raw)) / config_.counts_per_revolution);
        if (!std::isfinite(position)) return DecodeStatus::OutOfRange;
        unwrap_ = next;
        s.position = position;
        mark_position(s, f.timestamp_ns);
        if (has_effort) {
            s.torque = tau;
            mark_torque(s, f.timestamp_ns);
        }
        return DecodeStatus::Ok;
    }

private:
    JointConfig config_{};
    CountUnwrapper unwrap_{1ull << 32};
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

}  // namespace jacobid::hal::cia402
