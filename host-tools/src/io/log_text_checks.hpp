// SPDX-License-Identifier: MIT
#pragma once
// What a log's text says about how it was saved, checked by both log readers (the plain CSV reader and the
// --log-format reader) with one wording: the delimiter a one-column header or row suggests, line ends of
// bare CR (old Mac: the whole file read as one line, so 0 data rows), a UTF-16 encoding (every other byte
// NUL) and a UTF-8 byte order mark (an encoding marker, not part of the first cell).
#include <cstddef>
#include <string>
#include <string_view>

namespace jacobid::io {

// A row split into one cell that holds another common delimiter (';', tab, '|', ',', ' '): the file's
// delimiter is not the one used. Returns "is the delimiter ';'? (...)" with how to read it (`format`: the log
// format that set `delimiter`, empty for the plain CSV reader), or "" when nothing suggests one.
std::string delimiter_hint(std::size_t cells, std::string_view first_cell, char delimiter, const std::string& format);

// The text without a leading UTF-8 byte order mark.
std::string_view without_utf8_bom(std::string_view text);

// The number of cells most lines of `text` split into by `delimiter` (empty lines aside; of equally common
// counts, the one seen first); 0 for a text without a line.
std::size_t most_common_cell_count(std::string_view text, char delimiter);

// InputError("source:1: ...") for a text a log reader would misread: compressed (gzip, zip, xz, bzip2),
// UTF-16 (a byte order mark FF FE / FE FF, or NUL in every other byte), other NUL bytes (binary), and bare-CR
// line ends (a '\r' not followed by '\n' inside the first line). `first_line`: the text up to its first '\n'.
void require_readable_log_text(std::string_view first_line, const std::string& source);

// " (a decimal comma? ...)" for a cell that is a number once its ',' is a '.' ("0,5"), else "": the locale of
// a spreadsheet export, which "expected a number, got '0,5'" left to guess.
std::string decimal_comma_hint(std::string_view cell);

// Whether all of `s` is one number (fast_float's grammar), stored in `value`.
bool parses_as_number(std::string_view s, double& value);

}  // namespace jacobid::io
