// SPDX-License-Identifier: MIT
#include "io/log_text_checks.hpp"

#include <fast_float/fast_float.h>
#include <fmt/core.h>

#include <algorithm>
#include <unordered_map>

#include "core/errors.hpp"

namespace jacobid::io {

namespace {

std::string shown(char delimiter) { return delimiter == '\t' ? "\\t" : std::string(1, delimiter); }

}  // namespace

std::string delimiter_hint(std::size_t cells, std::string_view first_cell, char delimiter, const std::string& format) {
    if (cells != 1) return {};
    char best = 0;
    std::ptrdiff_t most = 0;
    for (const char candidate : {';', '\t', '|', ',', ' '}) {  // a space last: names may hold one
        if (candidate == delimiter) continue;
        const auto n = std::count(first_cell.begin(), first_cell.end(), candidate);
        if (n > most) most = n, best = candidate;
    }
    if (most == 0) return {};
    const std::string how = format.empty() ? fmt::format("this reader takes ','; a --log-format with delimiter: '{}' reads it", shown(best))
                                           : fmt::format("{} says delimiter: '{}'", format, shown(delimiter));
    return fmt::format("is the delimiter '{}'? ({})", shown(best), how);
}

std::string_view without_utf8_bom(std::string_view text) {
    constexpr std::string_view kUtf8Bom = "\xEF\xBB\xBF";
    if (text.substr(0, kUtf8Bom.size()) == kUtf8Bom) text.remove_prefix(kUtf8Bom.size());
    return text;
}

std::size_t most_common_cell_count(std::string_view text, char delimiter) {
    std::unordered_map<std::size_t, std::size_t> lines_with;  // cell count -> lines
    std::size_t best = 0, best_lines = 0;
    for (std::size_t pos = 0; pos < text.size();) {
        const std::size_t end = std::min(text.find('\n', pos), text.size());
        const std::string_view line = text.substr(pos, end - pos);
        pos = end + 1;
        if (line.find_first_not_of(" \t\r") == std::string_view::npos) continue;
        const std::size_t cells = static_cast<std::size_t>(std::count(line.begin(), line.end(), delimiter)) + 1;
        const std::size_t n = ++lines_with[cells];
        if (n > best_lines) best = cells, best_lines = n;
    }
    return best;
}

void require_readable_log_text(std::string_view first_line, const std::string& source) {
    // The magic numbers are looked for where the first name starts (after leading blanks, which names lose), so
    // that a table printed again from its names reads the same (fuzz_csv_log: a first name '\xFD7zXZ...' after a
    // tab was accepted, while its printed copy began with xz's magic number).
    const std::string_view start = first_line.substr(std::min(first_line.find_first_not_of(" \t"), first_line.size()));
    const auto begins = [](std::string_view text, std::string_view magic) { return text.substr(0, magic.size()) == magic; };
    const auto starts = [&](std::string_view magic) { return begins(start, magic); };
    const bool bzip2 = starts("BZh") && start.size() >= 10 && start[3] >= '1' && start[3] <= '9' && start.substr(4, 6) == "1AY&SY";
    if (starts("\x1F\x8B") || starts("PK\x03\x04") || starts("\xFD" "7zXZ") || bzip2) {
        throw InputError(fmt::format("{}:1: the file is compressed (gzip, zip, xz or bzip2): unpack it and give the CSV", source));
    }
    // UTF-16: a byte order mark, or NUL in every other byte of ASCII text; any other NUL: not a text file.
    std::size_t nul_even = 0, nul_odd = 0;
    const std::size_t probe = std::min<std::size_t>(first_line.size(), 256);
    for (std::size_t i = 0; i < probe; ++i) {
        if (first_line[i] == '\0') ++(i % 2 ? nul_odd : nul_even);
    }
    // A byte order mark is the file's very first bytes (FE or FF after blanks is refused below as not UTF-8).
    const bool utf16 = begins(first_line, "\xFF\xFE") || begins(first_line, "\xFE\xFF") || (probe >= 4 && std::min(nul_even, nul_odd) == 0 && std::max(nul_even, nul_odd) * 2 + 1 >= probe);
    if (utf16) {
        throw InputError(fmt::format("{}:1: the file is encoded as UTF-16 (NUL bytes between the characters): save it as UTF-8 or ASCII text", source));
    }
    // Bytes that UTF-8 never holds (C0, C1, F5-FF): another encoding (Latin-1's accented letters) or binary data.
    // Refused wherever they stand, so that no header name holds them (the UTF-16 byte order mark above among them).
    const auto never_utf8 = [](char c) {
        const auto u = static_cast<unsigned char>(c);
        return u == 0xC0 || u == 0xC1 || u >= 0xF5;
    };
    const auto bad = std::find_if(first_line.begin(), first_line.end(), never_utf8);
    if (bad != first_line.end()) {
        throw InputError(fmt::format("{}:1: byte {} is 0x{:02X}, which UTF-8 text never holds: another encoding (Latin-1?) or a binary file; "
                                     "save it as UTF-8 or ASCII text",
                                     source, bad - first_line.begin() + 1, static_cast<unsigned char>(*bad)));
    }
    // Control characters other than tab and CR: not text (random or binary data has them in its first line).
    const bool control = std::any_of(first_line.begin(), first_line.end(), [](char c) {
        const auto u = static_cast<unsigned char>(c);
        return u < 0x20 && c != '\t' && c != '\r';
    });
    if (control) throw InputError(fmt::format("{}:1: the file holds control characters (NUL, ...): a binary file, not a text log", source));
    const std::size_t cr = first_line.find('\r');
    if (cr != std::string_view::npos && cr + 1 < first_line.size()) {
        throw InputError(fmt::format("{}:1: the line ends are bare carriage returns (CR, old Mac style), so the whole file reads as one line: "
                                     "save it with LF or CRLF line ends",
                                     source));
    }
}

std::string decimal_comma_hint(std::string_view cell) {
    if (cell.find(',') == std::string_view::npos || cell.find('.') != std::string_view::npos) return {};
    std::string dotted(cell);
    std::replace(dotted.begin(), dotted.end(), ',', '.');
    double value = 0.0;
    return parses_as_number(dotted, value) ? " (a decimal comma? numbers are read with a '.')" : std::string();
}

bool parses_as_number(std::string_view s, double& value) {
    const auto r = fast_float::from_chars(s.data(), s.data() + s.size(), value);
    return r.ec == std::errc() && r.ptr == s.data() + s.size();
}

}  // namespace jacobid::io
