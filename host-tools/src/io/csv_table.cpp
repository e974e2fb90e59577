// SPDX-License-Identifier: MIT
#include "io/csv_table.hpp"

#include <fast_float/fast_float.h>
#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string_view>
#include <thread>

#include "core/errors.hpp"
#include "core/parallel_for.hpp"
#include "io/csv_rows.hpp"
#include "io/log_text_checks.hpp"
#include "io/printable_text.hpp"
#include "jacobid/yaml/input_file.hpp"

namespace jacobid::io {
namespace {

bool is_space(char c) { return c == ' ' || c == '\t'; }

}  // namespace

bool TextLines::next(std::string_view& out) {
    if (pos_ >= text_.size()) return false;
    std::size_t end = text_.find('\n', pos_);
    if (end == std::string::npos) end = text_.size();
    out = std::string_view(text_).substr(pos_, end - pos_);
    pos_ = end + 1;
    ++line_;
    return true;
}

std::string_view trim_cell(std::string_view s) {
    while (!s.empty() && is_space(s.front())) s.remove_prefix(1);
    while (!s.empty() && (is_space(s.back()) || s.back() == '\r')) s.remove_suffix(1);
    return s;
}

std::string printable_cell(std::string_view cell) { return printable_text(cell); }

std::string describe_columns(const std::vector<std::string>& names) {
    constexpr std::size_t kListed = 20;
    std::string all;
    for (std::size_t c = 0; c < names.size() && c < kListed; ++c) all += (c == 0 ? "" : ",") + printable_cell(names[c]);
    if (names.size() > kListed) all += fmt::format(",... ({} columns in all)", names.size());
    return all;
}

// The name index is built once (a header of 400 000 columns was checked for duplicates pairwise, minutes);
// a name twice is refused here, for read headers and for tables built from column names alike.
CsvTable::CsvTable(std::string source, std::vector<std::string> header)
    : source_(std::move(source)), header_(std::move(header)), columns_(header_.size()), loaded_(header_.size(), 1) {
    index_.reserve(header_.size());
    for (std::size_t c = 0; c < header_.size(); ++c) {
        const auto [it, fresh] = index_.emplace(header_[c], c);
        if (!fresh) {
            throw InputError(fmt::format("{}: duplicate column name '{}' (columns {} and {}): every column needs its own name", source_,
                                         printable_cell(header_[c]), it->second + 1, c + 1));
        }
    }
}

void CsvTable::keep_only(const std::function<bool(const std::string&)>& keep) {
    for (std::size_t c = 0; c < header_.size(); ++c) {
        loaded_[c] = keep(header_[c]) ? 1 : 0;
        if (!loaded_[c]) columns_[c] = {};
    }
    first_loaded_ = static_cast<std::size_t>(std::find(loaded_.begin(), loaded_.end(), 1) - loaded_.begin());
    if (first_loaded_ == loaded_.size()) throw std::logic_error(fmt::format("{}: told to keep none of its {} columns", source_, header_.size()));
}

void CsvTable::release(const std::string& name) {
    const auto it = index_.find(name);
    if (it == index_.end() || !loaded(it->second)) return;
    const auto others = std::count(loaded_.begin(), loaded_.end(), 1) - 1;
    if (others == 0) return;
    std::vector<double>().swap(columns_[it->second]);  // `= {}` would keep the capacity
    loaded_[it->second] = 0;
    first_loaded_ = static_cast<std::size_t>(std::find(loaded_.begin(), loaded_.end(), 1) - loaded_.begin());
}

bool CsvTable::has_column(const std::string& name) const {
    const auto it = index_.find(name);
    return it != index_.end() && loaded(it->second);
}

std::size_t CsvTable::column_index(const std::string& name) const {
    const auto it = index_.find(name);
    if (it == index_.end()) {
        throw InputError(fmt::format("{}: no column '{}' (columns: {})", source_, printable_cell(name), describe_columns(header_)));
    }
    if (!loaded(it->second)) throw std::logic_error(fmt::format("{}: column '{}' was read but not kept", source_, printable_cell(name)));
    return it->second;
}

namespace {

// The data rows of text[begin, end), whose first line is line number `first_line`, written into every
// column at rows [first_row, ...): one value per column per line. `last` says whether the range ends the
// text (only there may the last line be empty: a trailing newline). Returns the rows written.
std::size_t parse_row_range(const std::string& text, std::size_t begin, std::size_t end, std::size_t first_line, std::size_t first_row, bool last,
                            CsvTable& table) {
    const std::string& source = table.source();
    const std::vector<std::string>& header = table.header();
    const std::size_t width = header.size();
    std::size_t line = first_line, row_index = first_row;
    for (std::size_t pos = begin; pos < end; ++line) {
        std::size_t stop = text.find('\n', pos);
        if (stop == std::string::npos || stop > end) stop = end;
        const std::string_view row(text.data() + pos, stop - pos);
        pos = stop + 1;
        if (trim_cell(row).empty()) {
            if (last && pos >= end) break;  // trailing empty line
            throw InputError(fmt::format("{}:{}: empty line inside the data", source, line));
        }
        const char* p = row.data();
        const char* row_end = row.data() + row.size();
        for (std::size_t c = 0; c < width; ++c) {
            while (p < row_end && is_space(*p)) ++p;
            double value = 0;
            const auto r = fast_float::from_chars(p, row_end, value);
            const char* cell_end = p;
            while (cell_end < row_end && *cell_end != ',') ++cell_end;
            const auto cell = [&] { return printable_cell(trim_cell(std::string_view(p, static_cast<std::size_t>(cell_end - p)))); };
            if (r.ec != std::errc()) throw InputError(fmt::format("{}:{}: column '{}': expected a number, got '{}'", source, line, header[c], cell()));
            const char* q = r.ptr;
            while (q < row_end && (is_space(*q) || *q == '\r')) ++q;
            if (q != cell_end) throw InputError(fmt::format("{}:{}: column '{}': expected a number, got '{}'", source, line, header[c], cell()));
            if (!std::isfinite(value) || beyond_log_range(value)) {
                throw InputError(fmt::format("{}:{}: column '{}': value '{}' {}", source, line, header[c], cell(),
                                             std::isfinite(value) ? kBeyondLogRange : "is not finite (NaN or Inf)"));
            }
            if (table.loaded(c)) table.mutable_column(c)[row_index] = value;
            if (c + 1 < width) {
                if (cell_end == row_end) throw InputError(fmt::format("{}:{}: expected {} columns, found {}", source, line, width, c + 1));
                p = cell_end + 1;
            } else if (cell_end != row_end) {
                const auto extra = static_cast<std::size_t>(std::count(cell_end, row_end, ','));
                throw InputError(fmt::format("{}:{}: expected {} columns, found {}", source, line, width, width + extra));
            }
        }
        ++row_index;
    }
    return row_index - first_row;
}

}  // namespace

// Rows of text[begin, end) (whole lines; the text ends there only if `last`), the first being line
// `first_line`, appended to the table's columns. Long pieces are parsed in ranges of whole lines on every
// core: each range knows its first line number and row (counted first) and writes its own rows, and the
// first error by position is the one reported, so neither the table nor the message depends on the thread
// count.
void parse_csv_rows(const std::string& text, std::size_t begin, std::size_t end, std::size_t first_line, bool last, const CsvChunking& chunking,
                CsvTable& table) {
    if (begin >= end) return;
    const std::size_t bytes = end - begin;
    const std::size_t ranges = std::max<std::size_t>(
        1, std::min<std::size_t>(bytes / std::max<std::size_t>(1, chunking.range_bytes),
                                 chunking.max_ranges > 0 ? chunking.max_ranges : std::max(1u, std::thread::hardware_concurrency())));
    std::vector<std::size_t> starts = {begin};
    for (std::size_t r = 1; r < ranges; ++r) {
        const std::size_t newline = text.find('\n', begin + bytes * r / ranges);
        if (newline == std::string::npos || newline + 1 >= end || newline + 1 <= starts.back()) break;
        starts.push_back(newline + 1);
    }
    starts.push_back(end);
    const std::size_t count = starts.size() - 1;
    // Lines per range: every range but the last ends with a newline.
    const std::size_t rows_before = table.rows();
    std::vector<std::size_t> first_lines(count), first_rows(count);
    std::size_t lines = 0;
    for (std::size_t r = 0; r < count; ++r) {
        first_lines[r] = first_line + lines;
        first_rows[r] = rows_before + lines;
        lines += static_cast<std::size_t>(std::count(text.begin() + static_cast<std::ptrdiff_t>(starts[r]),
                                                      text.begin() + static_cast<std::ptrdiff_t>(starts[r + 1]), '\n'));
    }
    const std::size_t capacity = rows_before + lines + (text[end - 1] != '\n' ? 1 : 0);
    for (std::size_t c = 0; c < table.header().size(); ++c) {
        if (table.loaded(c)) table.mutable_column(c).resize(capacity);
    }
    std::vector<std::size_t> written(count, 0);
    ParallelForOptions pool;
    pool.threads = static_cast<int>(count);
    const std::vector<std::exception_ptr> errors = parallel_for(count, pool, [&](std::size_t r) {
        written[r] = parse_row_range(text, starts[r], starts[r + 1], first_lines[r], first_rows[r], last && r + 1 == count, table);
    });
    for (const auto& e : errors) {
        if (e) std::rethrow_exception(e);  // the earliest range's error: the first in the file
    }
    for (std::size_t c = 0; c < table.header().size(); ++c) {
        if (table.loaded(c)) table.mutable_column(c).resize(first_rows[count - 1] + written[count - 1]);
    }
}

// The header row's names (InputError for an empty file or a bad name).
std::vector<std::string> parse_csv_header(std::string_view row, const std::string& source) {
    if (trim_cell(row).empty()) throw InputError(fmt::format("{}:1: empty file, expected a header row", source));
    require_readable_log_text(row, source);
    // A UTF-8 byte order mark (spreadsheet exports) is an encoding marker, not part of the first name: kept,
    // it made the first column 'BOM+t', and "no column 't'" listed a 't' that looked the same.
    constexpr std::string_view kUtf8Bom = "\xEF\xBB\xBF";
    row = without_utf8_bom(row);
    std::vector<std::string> header;
    for (std::size_t start = 0;;) {
        const std::size_t comma = row.find(',', start);
        const std::string_view cell = trim_cell(row.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start));
        if (cell.empty()) throw InputError(fmt::format("{}:1: column {} has an empty name in the header", source, header.size() + 1));
        // Anywhere else the mark is an invisible character inside a name: refused rather than kept (a
        // name that prints alike but matches nothing) or dropped (the same file read twice would differ).
        if (cell.find(kUtf8Bom) != std::string_view::npos) {
            throw InputError(fmt::format("{}:1: column {}'s name holds an invisible byte order mark (U+FEFF) inside it", source, header.size() + 1));
        }
        double dummy;
        const auto r = fast_float::from_chars(cell.data(), cell.data() + cell.size(), dummy);
        if (r.ec == std::errc() && r.ptr == cell.data() + cell.size()) {
            throw InputError(fmt::format("{}:1: expected a header row of column names, found the number '{}'", source, printable_cell(cell)));
        }
        header.emplace_back(cell);
        if (comma == std::string_view::npos) break;
        start = comma + 1;
    }
    // A log has a time and at least one joint: a header of one name holding ';' is the wrong delimiter,
    // which was reported later as "no column 'q1' (columns: t;q1;tau1)", as if those were the columns.
    const std::string hint = delimiter_hint(header.size(), header.front(), ',', "");
    if (!hint.empty()) throw InputError(fmt::format("{}:1: the header '{}' is one column: {}", source, printable_cell(header.front()), hint));
    return header;
}

CsvTable parse_csv(const std::string& text, const std::string& source, const CsvChunking& chunking) {
    const std::size_t header_end = std::min(text.find('\n'), text.size());
    CsvTable table(source, parse_csv_header(std::string_view(text).substr(0, header_end), source));
    parse_csv_rows(text, std::min(header_end + 1, text.size()), text.size(), 2, true, chunking, table);
    return table;
}

std::string read_text_file(const std::string& path, const std::string& what) { return yaml::read_input_file<InputError>(path, what); }


}  // namespace jacobid::io
