// SPDX-License-Identifier: MIT
#pragma once
// Numeric CSV logs: a header row of column names, then one row per sample, every cell a finite number.
// Anything else is an InputError naming the file, line and column; nothing is skipped or guessed.
#include <cmath>
#include <cstddef>
#include <functional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace jacobid::io {

class CsvTable {
public:
    CsvTable() = default;
    CsvTable(std::string source, std::vector<std::string> header);

    const std::string& source() const { return source_; }
    const std::vector<std::string>& header() const { return header_; }
    std::size_t rows() const { return columns_.empty() ? 0 : columns_[first_loaded_].size(); }
    std::size_t columns() const { return header_.size(); }

    // Columns the reader checked but did not keep (read_csv's `keep`) are not loaded: has_column is false
    // for them, as if the file lacked them, and the header still names them in messages. Keeping none is a
    // caller's mistake (std::logic_error): a table without columns has no rows.
    void keep_only(const std::function<bool(const std::string&)>& keep);
    bool loaded(std::size_t index) const { return loaded_[index] != 0; }
    // Frees a column the caller has finished with (identify: the time column, once the log's sample period
    // and start are known: 29 MB of an hour at 1 kHz); afterwards as if not kept. The last loaded column
    // stays (it carries rows()); a column not loaded is left alone.
    void release(const std::string& name);
    bool has_column(const std::string& name) const;
    // The column's index; throws InputError naming the file and the available columns when missing
    // (std::logic_error when the file has it but the reader was told not to keep it: a caller's mistake).
    std::size_t column_index(const std::string& name) const;
    const std::vector<double>& column(const std::string& name) const { return columns_[column_index(name)]; }
    const std::vector<double>& column(std::size_t index) const { return columns_[index]; }
    std::vector<double>& mutable_column(std::size_t index) { return columns_[index]; }
    // Line number in the file of data row `row` (the header is line 1), for error messages. A piece of a
    // long log (io/csv_pieces.hpp) starts further down: its first row's line is set.
    std::size_t line_of_row(std::size_t row) const { return first_line_ + row; }
    void set_first_line(std::size_t line) { first_line_ = line; }

private:
    std::string source_;
    std::vector<std::string> header_;
    std::vector<std::vector<double>> columns_;  // column-major: what the numerics consume
    std::vector<char> loaded_;                  // per column
    std::size_t first_loaded_ = 0;              // the column rows() counts
    std::size_t first_line_ = 2;                // line of row 0
    std::unordered_map<std::string, std::size_t> index_;  // name -> column
};

// The lines of a text one at a time, numbered from 1 (a final line without '\n' counts; a '\r' before the
// '\n' stays, trim_cell drops it). Shared by the CSV reader and the raw-log reader (io/log_format.hpp).
class TextLines {
public:
    explicit TextLines(const std::string& text) : text_(text) {}
    bool next(std::string_view& out);
    std::size_t line() const { return line_; }    // number of the line last returned
    std::size_t offset() const { return pos_; }   // where the next line starts
    bool at_end() const { return pos_ >= text_.size(); }

private:
    const std::string& text_;
    std::size_t pos_ = 0, line_ = 0;
};

// The largest magnitude a log value may have: far beyond any measurement (nanosecond time stamps are ~1e18),
// and small enough that the sums of squares of its derivatives the identification forms cannot overflow
// (one torque cell of 1e200 made every identified value nan).
constexpr double kMaxLogValue = 1e30;
inline bool beyond_log_range(double v) { return std::abs(v) > kMaxLogValue; }
// What a message says of such a value.
constexpr const char* kBeyondLogRange = "is beyond +-1e30, which no measurement is (an outlier? its square would overflow the identification)";

// The whole file; InputError("path: cannot open <what>") when it cannot be read.
std::string read_text_file(const std::string& path, const std::string& what);

// A cell without surrounding spaces, tabs and a trailing '\r'.
std::string_view trim_cell(std::string_view s);
// A cell (or any user text) for a message: invisible and control characters escaped, the first 80
// characters, "..." when cut (io/printable_text.hpp).
std::string printable_cell(std::string_view cell);
// A header's names for a message ("t,q1,q2"), each one printable, the first 20 and the count when longer.
std::string describe_columns(const std::vector<std::string>& names);

// How a long CSV is read: streamed in blocks of whole lines (the text is never held whole), each block
// parsed in ranges of whole lines on up to max_ranges threads (0: one per core). The table and the
// messages do not depend on these; tests make them small to cross block and range boundaries.
struct CsvChunking {
    std::size_t block_bytes = std::size_t{16} << 20;
    std::size_t range_bytes = std::size_t{8} << 20;
    std::size_t max_ranges = 0;
};

// Which columns of a log a command keeps (by header name); every cell of the others is still checked. An
// hour of 6-axis simulated data has 25 columns of which identify reads 13: keeping them all held 0.35 GB
// more for nothing. Empty: every column.
using CsvColumnFilter = std::function<bool(const std::string& name)>;

// Reads `path`. Accepts ',' separators, optional spaces around cells, '\n' or '\r\n' line ends, a final
// line with or without '\n'; rejects empty files, empty or duplicate header names, rows with too few or
// too many cells, non-numeric cells and NaN/Inf; a header with none of the names `keep` keeps ("none of the
// header's columns ... is one this command reads": another robot's log, a compressed file).
CsvTable read_csv(const std::string& path, const CsvChunking& chunking = {}, const CsvColumnFilter& keep = {});
// Same, from text already in memory (`source` names it in messages).
CsvTable parse_csv(const std::string& text, const std::string& source, const CsvChunking& chunking = {});

}  // namespace jacobid::io
