// SPDX-License-Identifier: MIT
#pragma once
// The estimate datagram: one aligned row of the differentiator bank (raw q and tau at the aligned sample,
// q^, qd^, qdd^) for every joint, sent by the controller to the host recorder over UDP, one datagram per
// control cycle. The byte layout is specified in docs/stream-format.md; this file implements it.
//
// Two versions: 1 (44-byte joint blocks) and 2 (52-byte joint blocks: version 1's 44 bytes unchanged, then
// the contact monitor's external-torque estimate; stream flag `contact`, joint flag `contact`). A controller
// sends version 2 only when its monitor streams (fw.yaml `monitor:`), so a stream without the monitor stays
// byte for byte what version-1 receivers read; version-1 receivers refuse version 2 by its version field
// (UnsupportedVersion), never misread it.
//
// Every field is written and read byte by byte, little-endian, at the offsets of the spec (never by
// copying a struct), so the wire format does not depend on the compiler's padding or the CPU's byte
// order. Encoding and decoding are noexcept and allocation-free: the controller calls encode() on its
// cycle, and MaxJoints bounds the storage of a decoded datagram.
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "jacobid/span.hpp"

namespace jacobid::stream {

// "JDST" in the first four bytes: lets the receiver tell a stray datagram from ours before reading more.
constexpr std::array<std::uint8_t, 4> kDatagramMagic{0x4A, 0x44, 0x53, 0x54};
constexpr std::uint16_t kDatagramVersion = 1;         // without the contact monitor's fields
constexpr std::uint16_t kDatagramVersionMonitor = 2;  // with tau_ext per joint and the contact flags
constexpr std::size_t kDatagramHeaderSize = 48;
constexpr std::size_t kDatagramJointSize = 44;         // version 1
constexpr std::size_t kDatagramJointSizeMonitor = 52;  // version 2: + tau_ext (f64) at offset 44
// Largest UDP payload over IPv4 (65535 - 8 UDP - 20 IP): bounds the joint count the format can carry.
constexpr std::size_t kMaxUdpPayload = 65507;
constexpr std::size_t kProtocolMaxJoints = (kMaxUdpPayload - kDatagramHeaderSize) / kDatagramJointSize;  // 1487
constexpr std::size_t kProtocolMaxJointsMonitor = (kMaxUdpPayload - kDatagramHeaderSize) / kDatagramJointSizeMonitor;  // 1258

// Header flags (stream-wide). Unknown bits are rejected: new meanings need a new version.
enum StreamFlag : std::uint32_t {
    kStreamEstop = 1u << 0,    // the e-stop (safety input) is active: the robot is being stopped
    kStreamRestart = 1u << 1,  // first datagram after a controller (re)start or bank reset; history cleared
    kStreamContact = 1u << 2,  // version 2: the monitor confirmed a contact in this row (and acted on it)
};
constexpr std::uint32_t kStreamFlagsKnown = kStreamEstop | kStreamRestart;
constexpr std::uint32_t kStreamFlagsKnownMonitor = kStreamFlagsKnown | kStreamContact;

// Per-joint flags. They describe the aligned sample (the instant of `timestamp_ns`), not the newest cycle.
enum JointFlag : std::uint32_t {
    kJointStale = 1u << 0,        // the joint's frame for the aligned sample did not arrive: q, tau are held (or NaN)
    kJointDecodeError = 1u << 1,  // the frame for the aligned sample arrived but could not be decoded
    kJointWarmup = 1u << 2,       // estimates not valid yet: the windows are not full (after start/reset)
    kJointWindowStale = 1u << 3,  // some sample inside the estimator windows was stale: q^, qd^, qdd^ degraded
    kJointContact = 1u << 4,      // version 2: |tau_ext| of this joint is beyond its threshold in this row
};
constexpr std::uint32_t kJointFlagsKnown = kJointStale | kJointDecodeError | kJointWarmup | kJointWindowStale;
constexpr std::uint32_t kJointFlagsKnownMonitor = kJointFlagsKnown | kJointContact;
// q and tau are measurements: they may be non-finite only when there was no fresh, decodable measurement.
constexpr std::uint32_t kJointNoMeasurement = kJointStale | kJointDecodeError;

struct JointEstimate {
    double q = 0.0;             // raw measured position at the aligned sample (rad or m)
    double q_hat = 0.0;         // Jacobi estimate of the position (n = 0)
    double qd_hat = 0.0;        // velocity estimate (n = 1)
    double qdd_hat = 0.0;       // acceleration estimate (n = 2)
    double tau = 0.0;           // raw measured torque at the aligned sample (N m or N)
    std::uint32_t flags = 0;    // JointFlag bits
    double tau_ext = 0.0;       // version 2: the monitor's external-torque estimate at the aligned sample (N m or N)
};

template <std::size_t MaxJoints>
struct EstimateDatagram {
    static_assert(MaxJoints > 0 && MaxJoints <= kProtocolMaxJoints, "MaxJoints must be 1..1487 (one UDP datagram)");
    std::uint16_t version = kDatagramVersion;  // 1, or 2 with tau_ext and the contact flags
    std::uint32_t flags = 0;               // StreamFlag bits
    std::uint32_t delay_samples = 0;       // common delay of the estimates behind the newest sample
    std::uint64_t sequence = 0;            // +1 per datagram sent; gaps = lost datagrams
    std::uint64_t sample_index = 0;        // controller sample the row describes (BankOutput::sample_index)
    std::int64_t timestamp_ns = 0;         // time of the aligned sample, ns on the controller's clock
    double sample_period = 0.0;            // Ts in seconds
    std::size_t joint_count = 0;           // joints[0 .. joint_count) are meaningful
    std::array<JointEstimate, MaxJoints> joints{};
};

enum class DatagramStatus {
    Ok,
    Truncated,             // shorter than the header, or than the header + joint_count joint blocks
    Oversized,             // longer than the header + joint_count joint blocks (trailing bytes)
    BadMagic,              // the first four bytes are not "JDST"
    UnsupportedVersion,    // version other than 1 and 2
    NoJoints,              // joint count 0
    TooManyJoints,         // joint count above the receiver's capacity (MaxJoints)
    UnknownFlags,          // a stream or joint flag bit that version 1 does not define
    InvalidSamplePeriod,   // sample period not finite or <= 0
    NonFiniteMeasurement,  // q or tau not finite on a joint that is neither stale nor decode-error
    NonFiniteEstimate,     // q^, qd^ or qdd^ not finite on a joint without any flag
    BufferTooSmall,        // encode: the output buffer cannot hold the datagram
};

inline const char* describe(DatagramStatus s) noexcept {
    switch (s) {
        case DatagramStatus::Ok: return "ok";
        case DatagramStatus::Truncated: return "datagram is shorter than its header and joint blocks";
        case DatagramStatus::Oversized: return "datagram has trailing bytes after its joint blocks";
        case DatagramStatus::BadMagic: return "datagram does not start with the magic \"JDST\"";
        case DatagramStatus::UnsupportedVersion: return "unsupported estimate datagram version (this build reads versions 1 and 2)";
        case DatagramStatus::NoJoints: return "datagram has a joint count of 0";
        case DatagramStatus::TooManyJoints: return "joint count exceeds the receiver's capacity";
        case DatagramStatus::UnknownFlags: return "stream or joint flags have bits that the datagram's version does not define";
        case DatagramStatus::InvalidSamplePeriod: return "sample period must be a finite number > 0";
        case DatagramStatus::NonFiniteMeasurement: return "q or tau is not finite on a joint not flagged stale or decode-error";
        case DatagramStatus::NonFiniteEstimate: return "an estimate is not finite on a joint without flags";
        case DatagramStatus::BufferTooSmall: return "output buffer is too small for the datagram";
    }
    return "unknown datagram status";
}

constexpr std::size_t joint_block_size(std::uint16_t version) noexcept {
    return version == kDatagramVersionMonitor ? kDatagramJointSizeMonitor : kDatagramJointSize;
}
constexpr std::size_t datagram_size(std::size_t joint_count, std::uint16_t version = kDatagramVersion) noexcept {
    return kDatagramHeaderSize + joint_block_size(version) * joint_count;
}
constexpr bool known_version(std::uint16_t version) noexcept {
    return version == kDatagramVersion || version == kDatagramVersionMonitor;
}

namespace wire {

inline void put_u16(std::uint8_t* p, std::uint16_t v) noexcept {
    p[0] = static_cast<std::uint8_t>(v & 0xFFu);
    p[1] = static_cast<std::uint8_t>(v >> 8);
}
inline void put_u32(std::uint8_t* p, std::uint32_t v) noexcept {
    for (int i = 0; i < 4; ++i) p[i] = static_cast<std::uint8_t>((v >> (8 * i)) & 0xFFu);
}
inline void put_u64(std::uint8_t* p, std::uint64_t v) noexcept {
    for (int i = 0; i < 8; ++i) p[i] = static_cast<std::uint8_t>((v >> (8 * i)) & 0xFFu);
}
// IEEE-754 binary64: the bit pattern travels as a uint64 (memcpy is the defined way to get it).
inline void put_f64(std::uint8_t* p, double v) noexcept {
    std::uint64_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    put_u64(p, bits);
}
inline std::uint16_t get_u16(const std::uint8_t* p) noexcept { return static_cast<std::uint16_t>(p[0] | (p[1] << 8)); }
inline std::uint32_t get_u32(const std::uint8_t* p) noexcept {
    std::uint32_t v = 0;
    for (int i = 3; i >= 0; --i) v = (v << 8) | p[i];
    return v;
}
inline std::uint64_t get_u64(const std::uint8_t* p) noexcept {
    std::uint64_t v = 0;
    for (int i = 7; i >= 0; --i) v = (v << 8) | p[i];
    return v;
}
inline double get_f64(const std::uint8_t* p) noexcept {
    const std::uint64_t bits = get_u64(p);
    double v;
    std::memcpy(&v, &bits, sizeof v);
    return v;
}

}  // namespace wire

// Sample periods a controller can have: 1 ns (the kernels' own lower bound) to 1000 s. The bound keeps
// the recorder's time column, sample index x period, finite for any 64-bit sample index.
constexpr double kMinSamplePeriod = 1e-9;
constexpr double kMaxSamplePeriod = 1e3;

// The checks shared by encode and decode, so the controller cannot send what the host would reject.
inline DatagramStatus validate_values(std::uint16_t version, std::uint32_t stream_flags, double sample_period,
                                      const JointEstimate* joints, std::size_t count) noexcept {
    const bool monitor = version == kDatagramVersionMonitor;
    if ((stream_flags & ~(monitor ? kStreamFlagsKnownMonitor : kStreamFlagsKnown)) != 0) return DatagramStatus::UnknownFlags;
    if (!(sample_period >= kMinSamplePeriod && sample_period <= kMaxSamplePeriod)) return DatagramStatus::InvalidSamplePeriod;
    for (std::size_t j = 0; j < count; ++j) {
        const JointEstimate& e = joints[j];
        if ((e.flags & ~(monitor ? kJointFlagsKnownMonitor : kJointFlagsKnown)) != 0) return DatagramStatus::UnknownFlags;
        if ((e.flags & kJointNoMeasurement) == 0 && !(std::isfinite(e.q) && std::isfinite(e.tau))) {
            return DatagramStatus::NonFiniteMeasurement;
        }
        // The contact bit says the estimate is valid and large, so it does not excuse a non-finite one.
        const bool flagged = (e.flags & ~kJointContact) != 0;
        if (!flagged && !(std::isfinite(e.q_hat) && std::isfinite(e.qd_hat) && std::isfinite(e.qdd_hat))) {
            return DatagramStatus::NonFiniteEstimate;
        }
        if (monitor && !flagged && !std::isfinite(e.tau_ext)) return DatagramStatus::NonFiniteEstimate;
    }
    return DatagramStatus::Ok;
}

// Writes `d` into `out`; on Ok, `written` is the datagram size (datagram_size(d.joint_count)). Rejects
// what decode() would reject, so a bad row is caught on the controller, where it is cheapest to log.
template <std::size_t MaxJoints>
DatagramStatus encode(const EstimateDatagram<MaxJoints>& d, Span<std::uint8_t> out, std::size_t& written) noexcept {
    written = 0;
    if (d.joint_count == 0) return DatagramStatus::NoJoints;
    if (d.joint_count > MaxJoints) return DatagramStatus::TooManyJoints;
    if (!known_version(d.version)) return DatagramStatus::UnsupportedVersion;
    if (d.version == kDatagramVersionMonitor && d.joint_count > kProtocolMaxJointsMonitor) return DatagramStatus::TooManyJoints;
    const DatagramStatus values = validate_values(d.version, d.flags, d.sample_period, d.joints.data(), d.joint_count);
    if (values != DatagramStatus::Ok) return values;
    const std::size_t block = joint_block_size(d.version);
    const std::size_t size = datagram_size(d.joint_count, d.version);
    if (out.size() < size) return DatagramStatus::BufferTooSmall;

    std::uint8_t* p = out.data();
    for (std::size_t i = 0; i < kDatagramMagic.size(); ++i) p[i] = kDatagramMagic[i];
    wire::put_u16(p + 4, d.version);
    wire::put_u16(p + 6, static_cast<std::uint16_t>(d.joint_count));  // <= 1487 by the static_assert
    wire::put_u32(p + 8, d.flags);
    wire::put_u32(p + 12, d.delay_samples);
    wire::put_u64(p + 16, d.sequence);
    wire::put_u64(p + 24, d.sample_index);
    wire::put_u64(p + 32, static_cast<std::uint64_t>(d.timestamp_ns));  // two's complement bit pattern
    wire::put_f64(p + 40, d.sample_period);
    for (std::size_t j = 0; j < d.joint_count; ++j) {
        std::uint8_t* b = p + kDatagramHeaderSize + j * block;
        const JointEstimate& e = d.joints[j];
        wire::put_f64(b + 0, e.q);
        wire::put_f64(b + 8, e.q_hat);
        wire::put_f64(b + 16, e.qd_hat);
        wire::put_f64(b + 24, e.qdd_hat);
        wire::put_f64(b + 32, e.tau);
        wire::put_u32(b + 40, e.flags);
        if (d.version == kDatagramVersionMonitor) wire::put_f64(b + 44, e.tau_ext);
    }
    written = size;
    return DatagramStatus::Ok;
}

// Reads one datagram. The checks run in the order of the spec (size of the header, magic, version, joint
// count, exact size, then values), so the status names the first thing wrong. On anything but Ok, `out`
// is unspecified and must not be used.
template <std::size_t MaxJoints>
DatagramStatus decode(Span<const std::uint8_t> in, EstimateDatagram<MaxJoints>& out) noexcept {
    const std::uint8_t* p = in.data();
    // The magic and version are checked before the header length, so that a short stray datagram of
    // another protocol reads as "not ours" (BadMagic) rather than as a truncated one of ours.
    if (in.size() < kDatagramMagic.size()) return DatagramStatus::Truncated;
    for (std::size_t i = 0; i < kDatagramMagic.size(); ++i) {
        if (p[i] != kDatagramMagic[i]) return DatagramStatus::BadMagic;
    }
    if (in.size() < 6) return DatagramStatus::Truncated;
    const std::uint16_t version = wire::get_u16(p + 4);
    if (!known_version(version)) return DatagramStatus::UnsupportedVersion;
    if (in.size() < kDatagramHeaderSize) return DatagramStatus::Truncated;
    const std::size_t count = wire::get_u16(p + 6);
    if (count == 0) return DatagramStatus::NoJoints;
    if (count > MaxJoints) return DatagramStatus::TooManyJoints;
    const std::size_t block = joint_block_size(version);
    const std::size_t size = datagram_size(count, version);
    if (in.size() < size) return DatagramStatus::Truncated;
    if (in.size() > size) return DatagramStatus::Oversized;

    out.joint_count = count;
    out.version = version;
    out.flags = wire::get_u32(p + 8);
    out.delay_samples = wire::get_u32(p + 12);
    out.sequence = wire::get_u64(p + 16);
    out.sample_index = wire::get_u64(p + 24);
    out.timestamp_ns = static_cast<std::int64_t>(wire::get_u64(p + 32));
    out.sample_period = wire::get_f64(p + 40);
    for (std::size_t j = 0; j < count; ++j) {
        const std::uint8_t* b = p + kDatagramHeaderSize + j * block;
        JointEstimate& e = out.joints[j];
        e.q = wire::get_f64(b + 0);
        e.q_hat = wire::get_f64(b + 8);
        e.qd_hat = wire::get_f64(b + 16);
        e.qdd_hat = wire::get_f64(b + 24);
        e.tau = wire::get_f64(b + 32);
        e.flags = wire::get_u32(b + 40);
        e.tau_ext = version == kDatagramVersionMonitor ? wire::get_f64(b + 44) : 0.0;
    }
    return validate_values(version, out.flags, out.sample_period, out.joints.data(), count);
}

}  // namespace jacobid::stream
