// SPDX-License-Identifier: MIT
#include "io/csv_table.hpp"

#include <fast_float/fast_float.h>
#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string_view>

#include "core/errors.hpp"
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
    : source_(std::move(source)), header_(std::move(header)), columns_(header_.size()) {
    index_.reserve(header_.size());
    for (std::size_t c = 0; c < header_.size(); ++c) {
        const auto [it, fresh] = index_.emplace(header_[c], c);
        if (!fresh) {
            throw InputError(fmt::format("{}: duplicate column name '{}' (columns {} and {}): every column needs its own name", source_,
                                         printable_cell(header_[c]), it->second + 1, c + 1));
        }
    }
}

bool CsvTable::has_column(const std::string& name) const { return index_.count(name) != 0; }

std::size_t CsvTable::column_index(const std::string& name) const {
    const auto it = index_.find(name);
    if (it == index_.end()) {
        throw InputError(fmt::format("{}: no column '{}' (columns: {})", source_, printable_cell(name), describe_columns(header_)));
    }
    return it->second;
}

CsvTable parse_csv(const std::string& text, const std::string& source) {
    TextLines lines(text);
    auto next_line = [&](std::string_view& out) { return lines.next(out); };
    std::string_view row;
    if (!next_line(row) || trim_cell(row).empty()) throw InputError(fmt::format("{}:1: empty file, expected a header row", source));
    // A UTF-8 byte order mark (spreadsheet exports) is an encoding marker, not part of the first name: kept,
    // it made the first column 'BOM+t', and "no column 't'" listed a 't' that looked the same.
    constexpr std::string_view kUtf8Bom = "\xEF\xBB\xBF";
    if (row.substr(0, kUtf8Bom.size()) == kUtf8Bom) row.remove_prefix(kUtf8Bom.size());
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
    CsvTable table(source, header);
    const std::size_t width = header.size();
    // Reserve from a cheap estimate of the row count to avoid repeated growth on long logs.
    const std::size_t estimate = static_cast<std::size_t>(std::count(text.begin() + static_cast<std::ptrdiff_t>(std::min(lines.offset(), text.size())), text.end(), '\n')) + 1;
    for (std::size_t c = 0; c < width; ++c) table.mutable_column(c).reserve(estimate);
    while (next_line(row)) {
        const std::size_t line = lines.line();
        if (trim_cell(row).empty()) {
            if (lines.at_end()) break;  // trailing empty line
            throw InputError(fmt::format("{}:{}: empty line inside the data", source, line));
        }
        const char* p = row.data();
        const char* end = row.data() + row.size();
        for (std::size_t c = 0; c < width; ++c) {
            while (p < end && is_space(*p)) ++p;
            double value = 0;
            const auto r = fast_float::from_chars(p, end, value);
            const char* cell_end = p;
            while (cell_end < end && *cell_end != ',') ++cell_end;
            if (r.ec != std::errc()) {
                throw InputError(fmt::format("{}:{}: column '{}': expected a number, got '{}'", source, line, header[c],
                                             printable_cell(trim_cell(std::string_view(p, static_cast<std::size_t>(cell_end - p))))));
            }
            const char* q = r.ptr;
            while (q < end && (is_space(*q) || *q == '\r')) ++q;
            if (q != cell_end) {
                throw InputError(fmt::format("{}:{}: column '{}': expected a number, got '{}'", source, line, header[c],
                                             printable_cell(trim_cell(std::string_view(p, static_cast<std::size_t>(cell_end - p))))));
            }
            if (!std::isfinite(value) || beyond_log_range(value)) {
                throw InputError(fmt::format("{}:{}: column '{}': value '{}' {}", source, line, header[c],
                                             printable_cell(trim_cell(std::string_view(p, static_cast<std::size_t>(cell_end - p)))),
                                             std::isfinite(value) ? kBeyondLogRange : "is not finite (NaN or Inf)"));
            }
            table.mutable_column(c).push_back(value);
            if (c + 1 < width) {
                if (cell_end == end) {
                    throw InputError(fmt::format("{}:{}: expected {} columns, found {}", source, line, width, c + 1));
                }
                p = cell_end + 1;
            } else if (cell_end != end) {
                const auto extra = static_cast<std::size_t>(std::count(cell_end, end, ','));
                throw InputError(fmt::format("{}:{}: expected {} columns, found {}", source, line, width, width + extra));
            }
        }
    }
    return table;
}

std::string read_text_file(const std::string& path, const std::string& what) { return yaml::read_input_file<InputError>(path, what); }

CsvTable read_csv(const std::string& path) { return parse_csv(read_text_file(path, "file"), path); }

}  // namespace jacobid::io
