// SPDX-License-Identifier: MIT
#include "io/log_text_checks.hpp"

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
    const bool utf16_bom = first_line.substr(0, 2) == "\xFF\xFE" || first_line.substr(0, 2) == "\xFE\xFF";
    if (utf16_bom || first_line.find('\0') != std::string_view::npos) {
        throw InputError(fmt::format("{}:1: the file is encoded as UTF-16 (NUL bytes between the characters): save it as UTF-8 or ASCII text", source));
    }
    const std::size_t cr = first_line.find('\r');
    if (cr != std::string_view::npos && cr + 1 < first_line.size()) {
        throw InputError(fmt::format("{}:1: the line ends are bare carriage returns (CR, old Mac style), so the whole file reads as one line: "
                                     "save it with LF or CRLF line ends",
                                     source));
    }
}

}  // namespace jacobid::io
