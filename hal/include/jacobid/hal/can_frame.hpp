// SPDX-License-Identifier: MIT
#pragma once
// One CAN / CAN FD frame as the HAL passes it around, independent of the transport (SocketCAN, the
// in-process virtual bus, a future MCU driver). A plain value type with a fixed 64-byte payload, so queues
// of frames are fixed arrays and nothing on the cycle path allocates.
//
// Acceptance filters use the SocketCAN CAN_RAW_FILTER semantics, "(id & mask) == (filter.id & mask)",
// implemented once here (matches()) so that the virtual bus delivers exactly what the kernel would.
#include <array>
#include <cstddef>
#include <cstdint>

namespace jacobid::hal {

constexpr std::size_t kCanMaxDataLength = 8;     // classic CAN
constexpr std::size_t kCanFdMaxDataLength = 64;  // CAN FD
constexpr std::uint32_t kCanStandardIdMask = 0x7FFu;       // 11-bit identifier
constexpr std::uint32_t kCanExtendedIdMask = 0x1FFFFFFFu;  // 29-bit identifier

// Frame flags (bit set). Error frames never reach the decoders: the transports count them (see
// CanCounters) and drop them, so kError exists only for transports and tests that want to inject them.
enum CanFrameFlag : std::uint8_t {
    kCanExtended = 1u << 0,  // 29-bit identifier
    kCanRemote = 1u << 1,    // remote transmission request (no data); classic CAN only
    kCanError = 1u << 2,     // error frame (id holds the CAN_ERR_* class bits)
    kCanFd = 1u << 3,        // CAN FD frame (up to 64 bytes)
    kCanBitRateSwitch = 1u << 4,  // FD: data phase at the higher bit rate
    kCanErrorStateIndicator = 1u << 5,  // FD: transmitter is error passive
};

struct CanFrame {
    std::uint32_t id = 0;     // 11- or 29-bit identifier, without flags
    std::uint8_t len = 0;     // payload length in bytes: 0..8, or a CAN FD length up to 64 with kCanFd
    std::uint8_t flags = 0;   // CanFrameFlag bits
    std::array<std::uint8_t, kCanFdMaxDataLength> data{};
    // Receive time in ns (CLOCK_REALTIME from SO_TIMESTAMPNS for SocketCAN, the bus clock for the
    // virtual bus); 0 when the transport could not tell. Ignored on transmit.
    std::int64_t timestamp_ns = 0;

    constexpr bool extended() const noexcept { return (flags & kCanExtended) != 0; }
    constexpr bool remote() const noexcept { return (flags & kCanRemote) != 0; }
    constexpr bool error() const noexcept { return (flags & kCanError) != 0; }
    constexpr bool fd() const noexcept { return (flags & kCanFd) != 0; }
};

// CAN FD carries 0..8, 12, 16, 20, 24, 32, 48 or 64 bytes (the DLC codes 9..15 map to the last seven).
constexpr bool is_valid_fd_length(std::size_t len) noexcept {
    return len <= 8 || len == 12 || len == 16 || len == 20 || len == 24 || len == 32 || len == 48 || len == 64;
}

// A frame a transport may put on the wire: identifier within its width, length legal for the frame
// type, no remote flag on FD frames (FD has no RTR), and FD-only flags only on FD frames.
constexpr bool is_valid_frame(const CanFrame& f) noexcept {
    const std::uint32_t id_mask = f.extended() ? kCanExtendedIdMask : kCanStandardIdMask;
    if ((f.id & ~id_mask) != 0) return false;
    if (f.fd()) return !f.remote() && is_valid_fd_length(f.len);
    if ((f.flags & (kCanBitRateSwitch | kCanErrorStateIndicator)) != 0) return false;
    return f.len <= kCanMaxDataLength;
}

// Which identifier formats an acceptance filter lets through.
enum class CanIdFormat : std::uint8_t { Standard, Extended, Any };

// One acceptance filter: a frame passes when (frame.id & mask) == (id & mask) and its format matches.
// Remote frames are refused unless accept_remote is set: no device profile decodes RTR frames, and a
// remote request carrying a telemetry id must not be mistaken for a short reply. A set of filters
// passes a frame when any one does (as CAN_RAW_FILTER); an empty set passes everything.
struct CanFilter {
    std::uint32_t id = 0;
    std::uint32_t mask = 0;  // 0 = accept every id of the format
    CanIdFormat format = CanIdFormat::Standard;
    bool accept_remote = false;
};

// Accept exactly one identifier.
constexpr CanFilter exact_filter(std::uint32_t id, bool extended = false) noexcept {
    return CanFilter{id, extended ? kCanExtendedIdMask : kCanStandardIdMask,
                     extended ? CanIdFormat::Extended : CanIdFormat::Standard, false};
}

constexpr bool matches(const CanFilter& filter, const CanFrame& frame) noexcept {
    if (frame.remote() && !filter.accept_remote) return false;
    if (filter.format == CanIdFormat::Standard && frame.extended()) return false;
    if (filter.format == CanIdFormat::Extended && !frame.extended()) return false;
    return (frame.id & filter.mask) == (filter.id & filter.mask);
}

template <typename Filters>
constexpr bool matches_any(const Filters& filters, std::size_t count, const CanFrame& frame) noexcept {
    if (count == 0) return true;
    for (std::size_t i = 0; i < count; ++i) {
        if (matches(filters[i], frame)) return true;
    }
    return false;
}

}  // namespace jacobid::hal
