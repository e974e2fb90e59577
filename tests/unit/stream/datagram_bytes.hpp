// SPDX-License-Identifier: MIT
#pragma once
// Bytes written by hand for the estimate datagram tests (versions 1 and 2): hex text to bytes, and a
// double's IEEE-754 bit pattern for bit-exact comparisons.
#include <cctype>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace jacobid::test {

using Bytes = std::vector<std::uint8_t>;

inline Bytes from_hex(const std::string& hex) {
    Bytes out;
    std::string digits;
    for (char c : hex) {
        if (std::isxdigit(static_cast<unsigned char>(c))) digits += c;
    }
    for (std::size_t i = 0; i + 1 < digits.size(); i += 2) out.push_back(static_cast<std::uint8_t>(std::stoul(digits.substr(i, 2), nullptr, 16)));
    return out;
}

inline std::uint64_t bits_of(double v) {
    std::uint64_t b;
    std::memcpy(&b, &v, sizeof b);
    return b;
}

}  // namespace jacobid::test
