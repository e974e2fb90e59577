// SPDX-License-Identifier: MIT
#pragma once
// Byte-level packing shared by the device profiles: fixed-width integers in either byte order, IEEE-754
// float32, and bit fields of any width. Built from shifts, never from casting the payload to a wider
// type, so the result does not depend on the host's endianness or alignment.
#include <cstddef>
#include <cstdint>
#include <cstring>

namespace jacobid::hal {

enum class ByteOrder : std::uint8_t {
    LittleEndian,  // least significant byte first (CANopen, ODrive)
    BigEndian,     // most significant byte first ("Motorola"; MIT-mode fields are big-endian)
};

// Unsigned integer of `bytes` bytes (1..8) starting at p.
inline std::uint64_t load_uint(const std::uint8_t* p, std::size_t bytes, ByteOrder order) noexcept {
    std::uint64_t v = 0;
    for (std::size_t i = 0; i < bytes; ++i) {
        const std::size_t k = order == ByteOrder::BigEndian ? i : bytes - 1 - i;
        v = (v << 8) | p[k];
    }
    return v;
}

inline void store_uint(std::uint8_t* p, std::size_t bytes, ByteOrder order, std::uint64_t v) noexcept {
    for (std::size_t i = 0; i < bytes; ++i) {
        const std::size_t k = order == ByteOrder::LittleEndian ? i : bytes - 1 - i;
        p[k] = static_cast<std::uint8_t>(v & 0xFFu);
        v >>= 8;
    }
}

// Two's complement sign extension of the low `bits` bits (1..64).
constexpr std::int64_t sign_extend(std::uint64_t v, unsigned bits) noexcept {
    if (bits >= 64) return static_cast<std::int64_t>(v);
    const std::uint64_t sign = 1ull << (bits - 1);
    const std::uint64_t low = v & ((1ull << bits) - 1);
    return static_cast<std::int64_t>(low ^ sign) - static_cast<std::int64_t>(sign);
}

constexpr std::uint64_t low_bits_mask(unsigned bits) noexcept {
    return bits >= 64 ? ~0ull : (1ull << bits) - 1;
}

inline float load_float32_le(const std::uint8_t* p) noexcept {
    const auto bits = static_cast<std::uint32_t>(load_uint(p, 4, ByteOrder::LittleEndian));
    float f;
    std::memcpy(&f, &bits, sizeof f);
    return f;
}

inline void store_float32_le(std::uint8_t* p, float f) noexcept {
    std::uint32_t bits;
    std::memcpy(&bits, &f, sizeof bits);
    store_uint(p, 4, ByteOrder::LittleEndian, bits);
}

}  // namespace jacobid::hal
