// SPDX-License-Identifier: MIT
#pragma once
// Helpers for the HAL tests: frames written as hex byte lists.
#include <cstdint>
#include <initializer_list>
#include <string>

#include "jacobid/hal/can_frame.hpp"

namespace jacobid::hal::test {

inline CanFrame frame(std::uint32_t id, std::initializer_list<std::uint8_t> bytes, std::uint8_t flags = 0) {
    CanFrame f;
    f.id = id;
    f.flags = flags;
    f.len = static_cast<std::uint8_t>(bytes.size());
    std::size_t i = 0;
    for (auto b : bytes) f.data[i++] = b;
    return f;
}

// "01 FF 0A" for failure messages.
inline std::string hex(const CanFrame& f) {
    static const char* digits = "0123456789ABCDEF";
    std::string s;
    for (std::size_t i = 0; i < f.len; ++i) {
        if (i) s += ' ';
        s += digits[f.data[i] >> 4];
        s += digits[f.data[i] & 0xF];
    }
    return s;
}

}  // namespace jacobid::hal::test
