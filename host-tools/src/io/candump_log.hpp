// SPDX-License-Identifier: MIT
#pragma once
// candump log files ("candump -L", can-utils' log format; also what python-can's CanutilsLogReader reads):
//
//   (1700000000.123456) can0 123#DEADBEEF        classic frame, 11-bit id (3 hex digits)
//   (1700000000.123456) can0 12345678#00FF       classic frame, 29-bit id (8 hex digits)
//   (1700000000.123456) can0 123#R               remote frame; "123#R4" requests 4 bytes
//   (1700000000.123456) can0 123##1DEADBEEF      CAN FD: one hex digit of flags (1 BRS, 2 ESI, 4 FDF), data
//   (1700000000.123456) can0 20000080#0000...    error frame: 8-digit id with CAN_ERR_FLAG (0x20000000) set
//   an optional " R" / " T" after the frame marks received / transmitted frames (newer candump -x).
//
// Frames are parsed into the HAL's frame type (hal/include/jacobid/hal/can_frame.hpp), so a log replays
// through the same device profiles as a live bus. Anything the format does not allow is an InputError
// "file:line: ..." saying what was expected; nothing is skipped except empty lines.
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "jacobid/hal/can_frame.hpp"

namespace jacobid::io {

struct CandumpRecord {
    hal::CanFrame frame;     // timestamp_ns holds the log's time stamp, exactly (no double rounding)
    std::string interface;   // e.g. "can0"
    char direction = 0;      // 'R' or 'T' when the line says so, 0 when it does not
    std::size_t line = 0;    // 1-based line in the file, for messages about this frame
};

// Parses one non-empty line; `source` and `line_number` only name the place in errors.
CandumpRecord parse_candump_line(std::string_view line, const std::string& source, std::size_t line_number);
// Every frame of a log, in file order (time stamps are not required to increase: candump writes them as
// the kernel delivers them, and merged multi-interface logs interleave).
std::vector<CandumpRecord> parse_candump_log(const std::string& text, const std::string& source);
std::vector<CandumpRecord> read_candump_log(const std::string& path);

}  // namespace jacobid::io
