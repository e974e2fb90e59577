// SPDX-License-Identifier: MIT
#pragma once
// The CSV parser's two steps, shared by the reader of text in memory (parse_csv) and the streamed reader
// of files (io/csv_pieces.hpp). Every problem is an InputError naming the file, line and column.
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "io/csv_table.hpp"

namespace jacobid::io {

// The header row's names (InputError for an empty file or a bad name).
std::vector<std::string> parse_csv_header(std::string_view row, const std::string& source);

// Rows of text[begin, end) (whole lines; the text ends there only if `last`), the first being line
// `first_line`, appended to the table's loaded columns; parsed in ranges on up to chunking.max_ranges threads.
void parse_csv_rows(const std::string& text, std::size_t begin, std::size_t end, std::size_t first_line, bool last, const CsvChunking& chunking,
                    CsvTable& table);

}  // namespace jacobid::io
