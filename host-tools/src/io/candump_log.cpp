// SPDX-License-Identifier: MIT
#include "io/candump_log.hpp"

#include <fmt/core.h>

#include <cstdint>
#include <fstream>
#include <limits>
#include <sstream>

#include "core/errors.hpp"
#include "jacobid/yaml/input_file.hpp"

namespace jacobid::io {
namespace {

constexpr std::uint32_t kCanErrFlag = 0x20000000u;  // linux/can.h CAN_ERR_FLAG, as candump prints it
constexpr std::uint8_t kFdFlagBrs = 0x1;            // linux/can.h CANFD_BRS
constexpr std::uint8_t kFdFlagEsi = 0x2;            // CANFD_ESI
constexpr std::uint8_t kFdFlagFdf = 0x4;            // CANFD_FDF (set by newer kernels; carries no meaning here)

bool is_field_separator(char c) { return c == ' ' || c == '\t' || c == '\r'; }
bool is_digit(char c) { return c >= '0' && c <= '9'; }

int hex_value(char c) {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
}

std::string shown(std::string_view s) {
    std::string out(s.substr(0, 48));
    return s.size() > 48 ? out + "..." : out;
}

// Splits the line into whitespace-separated fields (python-can's str.split() does the same).
std::vector<std::string_view> fields_of(std::string_view line) {
    std::vector<std::string_view> fields;
    std::size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && is_field_separator(line[i])) ++i;
        const std::size_t start = i;
        while (i < line.size() && !is_field_separator(line[i])) ++i;
        if (i > start) fields.push_back(line.substr(start, i - start));
    }
    return fields;
}

struct Where {
    const std::string& source;
    std::size_t line;
    [[noreturn]] void fail(const std::string& what) const { throw InputError(fmt::format("{}:{}: {}", source, line, what)); }
};

// "(seconds.fraction)" to integer nanoseconds, exactly: candump prints microseconds, and a double would
// round a present-day epoch time to about 0.24 us.
std::int64_t parse_timestamp(std::string_view s, const Where& at) {
    const auto bad = [&] {
        at.fail(fmt::format("expected a time stamp '(seconds.fraction)' like '(1700000000.123456)', found '{}'", shown(s)));
    };
    if (s.size() < 4 || s.front() != '(' || s.back() != ')') bad();
    const std::string_view body = s.substr(1, s.size() - 2);
    const std::size_t dot = body.find('.');
    if (dot == std::string_view::npos || dot == 0 || dot + 1 == body.size()) bad();
    const std::string_view whole = body.substr(0, dot), fraction = body.substr(dot + 1);
    for (char c : whole) {
        if (!is_digit(c)) bad();
    }
    for (char c : fraction) {
        if (!is_digit(c)) bad();
    }
    if (fraction.size() > 9) at.fail(fmt::format("time stamp '{}' has more than 9 decimals (nanoseconds)", shown(s)));
    constexpr std::int64_t kMaxSeconds = std::numeric_limits<std::int64_t>::max() / 1000000000 - 1;
    std::int64_t seconds = 0;
    for (char c : whole) {
        seconds = seconds * 10 + (c - '0');
        if (seconds > kMaxSeconds) at.fail(fmt::format("time stamp '{}' is too large (beyond the year 2262 in ns)", shown(s)));
    }
    std::int64_t ns = 0;
    for (std::size_t i = 0; i < 9; ++i) ns = ns * 10 + (i < fraction.size() ? fraction[i] - '0' : 0);
    return seconds * 1000000000 + ns;
}

// Hex byte pairs into frame.data; returns the byte count.
std::size_t parse_data(std::string_view hex, std::size_t capacity, hal::CanFrame& frame, const Where& at) {
    // Syntax that other can-utils tools accept but this reader does not, named before the generic checks.
    if (hex.find('.') != std::string_view::npos) at.fail(fmt::format("data '{}': '.' separators are cansend syntax; candump -L writes plain hex", shown(hex)));
    if (hex.find('_') != std::string_view::npos) at.fail(fmt::format("data '{}': raw DLC suffix '_<dlc>' (len8_dlc) is not supported", shown(hex)));
    if (hex.size() % 2 != 0) at.fail(fmt::format("data '{}' has an odd number of hex digits (expected whole bytes, 2 digits each)", shown(hex)));
    if (hex.size() / 2 > capacity) at.fail(fmt::format("data '{}' has {} bytes, more than the {} a {} frame carries", shown(hex), hex.size() / 2, capacity, capacity == 8 ? "classic CAN" : "CAN FD"));
    for (std::size_t i = 0; i < hex.size(); i += 2) {
        const int hi = hex_value(hex[i]), lo = hex_value(hex[i + 1]);
        if (hi < 0 || lo < 0) {
            const char bad = hi < 0 ? hex[i] : hex[i + 1];
            at.fail(fmt::format("data '{}': '{}' is not a hex digit", shown(hex), bad));
        }
        frame.data[i / 2] = static_cast<std::uint8_t>(hi * 16 + lo);
    }
    return hex.size() / 2;
}

void parse_frame(std::string_view text, hal::CanFrame& frame, const Where& at) {
    const std::size_t hash = text.find('#');
    if (hash == std::string_view::npos) at.fail(fmt::format("expected a frame '<id>#<data>' like '123#DEADBEEF', found '{}'", shown(text)));
    const std::string_view id_text = text.substr(0, hash);
    if (id_text.size() != 3 && id_text.size() != 8) {
        at.fail(fmt::format("identifier '{}' must have 3 hex digits (standard) or 8 (extended)", shown(id_text)));
    }
    std::uint32_t id = 0;
    for (char c : id_text) {
        const int v = hex_value(c);
        if (v < 0) at.fail(fmt::format("identifier '{}': '{}' is not a hex digit", shown(id_text), c));
        id = id * 16 + static_cast<std::uint32_t>(v);
    }
    std::string_view rest = text.substr(hash + 1);
    if (id_text.size() == 3) {
        if (id > hal::kCanStandardIdMask) at.fail(fmt::format("standard identifier {} exceeds 7FF (11 bits)", id_text));
    } else if ((id & kCanErrFlag) != 0) {
        // Error frame: the low 29 bits are the CAN_ERR_* class, the 8 data bytes the details.
        if ((id & ~(kCanErrFlag | hal::kCanExtendedIdMask)) != 0) at.fail(fmt::format("identifier {} has bits beyond 29 bits and CAN_ERR_FLAG", id_text));
        frame.flags = hal::kCanError;
        frame.id = id & hal::kCanExtendedIdMask;
        if (!rest.empty() && rest.front() == '#') at.fail("error frame cannot be a CAN FD frame ('##')");
        frame.len = static_cast<std::uint8_t>(parse_data(rest, hal::kCanMaxDataLength, frame, at));
        return;
    } else {
        if (id > hal::kCanExtendedIdMask) at.fail(fmt::format("extended identifier {} exceeds 1FFFFFFF (29 bits)", id_text));
        frame.flags = hal::kCanExtended;
    }
    frame.id = id;

    if (!rest.empty() && rest.front() == '#') {  // CAN FD: "##<flags><data>"
        if (rest.size() < 2) at.fail(fmt::format("CAN FD frame '{}': expected a flags digit after '##'", shown(text)));
        const int fd_flags = hex_value(rest[1]);
        if (fd_flags < 0 || (fd_flags & ~(kFdFlagBrs | kFdFlagEsi | kFdFlagFdf)) != 0) {
            at.fail(fmt::format("CAN FD frame '{}': flags digit '{}' is not 0-7 (1 BRS, 2 ESI, 4 FDF)", shown(text), rest[1]));
        }
        frame.flags = static_cast<std::uint8_t>(frame.flags | hal::kCanFd);
        if ((fd_flags & kFdFlagBrs) != 0) frame.flags = static_cast<std::uint8_t>(frame.flags | hal::kCanBitRateSwitch);
        if ((fd_flags & kFdFlagEsi) != 0) frame.flags = static_cast<std::uint8_t>(frame.flags | hal::kCanErrorStateIndicator);
        const std::size_t len = parse_data(rest.substr(2), hal::kCanFdMaxDataLength, frame, at);
        if (!hal::is_valid_fd_length(len)) {
            at.fail(fmt::format("CAN FD frame '{}' has {} data bytes; FD lengths are 0-8, 12, 16, 20, 24, 32, 48 or 64", shown(text), len));
        }
        frame.len = static_cast<std::uint8_t>(len);
        return;
    }
    if (!rest.empty() && (rest.front() == 'R' || rest.front() == 'r')) {  // remote frame, optional length digit
        frame.flags = static_cast<std::uint8_t>(frame.flags | hal::kCanRemote);
        if (rest.size() > 2 || (rest.size() == 2 && !(rest[1] >= '0' && rest[1] <= '8'))) {
            at.fail(fmt::format("remote frame '{}': expected 'R' or 'R' and a length digit 0-8", shown(text)));
        }
        frame.len = static_cast<std::uint8_t>(rest.size() == 2 ? rest[1] - '0' : 0);
        return;
    }
    frame.len = static_cast<std::uint8_t>(parse_data(rest, hal::kCanMaxDataLength, frame, at));
}

}  // namespace

CandumpRecord parse_candump_line(std::string_view line, const std::string& source, std::size_t line_number) {
    const Where at{source, line_number};
    const std::vector<std::string_view> fields = fields_of(line);
    if (fields.size() < 3 || fields.size() > 4) {
        at.fail(fmt::format("expected '(time) interface id#data [R|T]', found {} field(s) in '{}'", fields.size(), shown(line)));
    }
    CandumpRecord r;
    r.line = line_number;
    r.frame.timestamp_ns = parse_timestamp(fields[0], at);
    r.interface = std::string(fields[1]);
    parse_frame(fields[2], r.frame, at);
    if (fields.size() == 4) {
        const std::string_view d = fields[3];
        if (d != "R" && d != "T" && d != "r" && d != "t") at.fail(fmt::format("expected direction 'R' or 'T' after the frame, found '{}'", shown(d)));
        r.direction = d[0] == 'r' || d[0] == 'R' ? 'R' : 'T';
    }
    return r;
}

std::vector<CandumpRecord> parse_candump_log(const std::string& text, const std::string& source) {
    std::vector<CandumpRecord> records;
    std::size_t pos = 0, line = 0;
    while (pos < text.size()) {
        std::size_t end = text.find('\n', pos);
        if (end == std::string::npos) end = text.size();
        const std::string_view l = std::string_view(text).substr(pos, end - pos);
        pos = end + 1;
        ++line;
        if (fields_of(l).empty()) continue;  // blank lines (a trailing newline, an editor's extra line)
        records.push_back(parse_candump_line(l, source, line));
    }
    return records;
}

std::vector<CandumpRecord> read_candump_log(const std::string& path) {
    return parse_candump_log(yaml::read_input_file<InputError>(path, "the candump log"), path);
}

}  // namespace jacobid::io
