// SPDX-License-Identifier: MIT
#include "io/printable_text.hpp"

#include <fmt/core.h>

#include <cstdint>
#include <vector>

namespace jacobid::io {
namespace {

// Code points that print as nothing, or reorder the text around them (Unicode's Default_Ignorable and the
// bidirectional controls), beside the C0/C1 controls.
bool invisible(std::uint32_t c) {
    return c < 0x20 || (c >= 0x7F && c <= 0x9F) || c == 0xAD || c == 0x34F || c == 0x61C || c == 0x115F || c == 0x1160 ||
           (c >= 0x17B4 && c <= 0x17B5) || (c >= 0x180B && c <= 0x180F) || (c >= 0x200B && c <= 0x200F) || (c >= 0x2028 && c <= 0x202E) ||
           (c >= 0x2060 && c <= 0x206F) || c == 0x3164 || (c >= 0xFE00 && c <= 0xFE0F) || c == 0xFEFF || c == 0xFFA0 ||
           (c >= 0xFFF0 && c <= 0xFFFB) || (c >= 0x1D173 && c <= 0x1D17A) || (c >= 0xE0000 && c <= 0xE0FFF);
}

// The code point starting at text[i] and its length in bytes; length 0 for a byte that does not start
// a valid, shortest-form UTF-8 sequence.
std::size_t decode_utf8(std::string_view text, std::size_t i, std::uint32_t& c) {
    const auto byte = [&](std::size_t k) { return static_cast<std::uint8_t>(text[k]); };
    const std::uint8_t b = byte(i);
    std::size_t n = 0;
    if (b < 0x80) {
        c = b;
        return 1;
    }
    if (b >= 0xC2 && b <= 0xDF) n = 2, c = b & 0x1Fu;
    else if (b >= 0xE0 && b <= 0xEF) n = 3, c = b & 0x0Fu;
    else if (b >= 0xF0 && b <= 0xF4) n = 4, c = b & 0x07u;
    else return 0;
    if (i + n > text.size()) return 0;
    for (std::size_t k = 1; k < n; ++k) {
        if ((byte(i + k) & 0xC0u) != 0x80u) return 0;
        c = (c << 6) | (byte(i + k) & 0x3Fu);
    }
    const bool overlong = (n == 3 && c < 0x800) || (n == 4 && c < 0x10000);
    if (overlong || c > 0x10FFFF || (c >= 0xD800 && c <= 0xDFFF)) return 0;
    return n;
}

// One printed character per entry: a code point as it is, or its escape.
std::vector<std::string> printed_characters(std::string_view text, std::size_t limit) {
    std::vector<std::string> out;
    for (std::size_t i = 0; i < text.size() && out.size() < limit;) {
        std::uint32_t c = 0;
        const std::size_t n = decode_utf8(text, i, c);
        if (n == 0) {
            out.push_back(fmt::format("\\x{:02x}", static_cast<std::uint8_t>(text[i])));
            i += 1;
            continue;
        }
        if (c == 0) out.emplace_back("\\0");
        else if (c == '\t') out.emplace_back("\\t");
        else if (c == '\n') out.emplace_back("\\n");
        else if (c == '\r') out.emplace_back("\\r");
        else if (c < 0x80 && invisible(c)) out.push_back(fmt::format("\\x{:02x}", c));
        else if (invisible(c)) out.push_back(c > 0xFFFF ? fmt::format("\\U{:08x}", c) : fmt::format("\\u{:04x}", c));
        else out.emplace_back(text.substr(i, n));
        i += n;
    }
    return out;
}

std::string joined(const std::vector<std::string>& characters, std::size_t from, std::size_t to) {
    std::string s;
    for (std::size_t k = from; k < to; ++k) s += characters[k];
    return s;
}

}  // namespace

std::string printable_text(std::string_view text, std::size_t max_chars) {
    const std::vector<std::string> characters = printed_characters(text, max_chars + 1);
    if (characters.size() <= max_chars) return joined(characters, 0, characters.size());
    return joined(characters, 0, max_chars) + "...";
}

std::string printable_message(std::string_view message) {
    const std::vector<std::string> characters = printed_characters(message, message.size());
    if (characters.size() <= kMessageChars) return joined(characters, 0, characters.size());
    const std::size_t head = kMessageChars * 3 / 4, tail = kMessageChars / 4;
    return joined(characters, 0, head) + fmt::format(" ... ({} characters left out) ... ", characters.size() - head - tail) +
           joined(characters, characters.size() - tail, characters.size());
}

}  // namespace jacobid::io
