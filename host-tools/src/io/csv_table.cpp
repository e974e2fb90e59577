// SPDX-License-Identifier: MIT
#include "io/csv_table.hpp"

#include <fast_float/fast_float.h>
#include <fmt/core.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <future>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <thread>

#include "core/errors.hpp"
#include "core/huge_pages.hpp"
#include "core/parallel_for.hpp"
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

// Rows of text[begin, end) (whole lines; the text ends there only if `last`), the first being line
// `first_line`, appended to the table's columns. Long pieces are parsed in ranges of whole lines on every
// core: each range knows its first line number and row (counted first) and writes its own rows, and the
// first error by position is the one reported, so neither the table nor the message depends on the thread
// count.
void parse_rows(const std::string& text, std::size_t begin, std::size_t end, std::size_t first_line, bool last, const CsvChunking& chunking,
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
std::vector<std::string> parse_header(std::string_view row, const std::string& source) {
    if (trim_cell(row).empty()) throw InputError(fmt::format("{}:1: empty file, expected a header row", source));
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
    return header;
}

}  // namespace

CsvTable parse_csv(const std::string& text, const std::string& source, const CsvChunking& chunking) {
    const std::size_t header_end = std::min(text.find('\n'), text.size());
    CsvTable table(source, parse_header(std::string_view(text).substr(0, header_end), source));
    parse_rows(text, std::min(header_end + 1, text.size()), text.size(), 2, true, chunking, table);
    return table;
}

std::string read_text_file(const std::string& path, const std::string& what) { return yaml::read_input_file<InputError>(path, what); }

// Streamed in blocks of whole lines: the text of a long log is never held whole (a 1-hour 6-axis log is
// 1.4 GB of text for 0.7 GB of numbers), and each block is parsed as it arrives.
namespace {

// The file block by block, each next block read on a second thread while the caller parses the last one:
// reading (a copy out of the page cache, 0.35 s for an hour's 1.4 GB) no longer waits for the parse. The
// block is never zero-filled (a std::string resized by a block was: 0.3 s of memset per hour).
class BlockReader {
public:
    BlockReader(const std::string& path, std::size_t block_bytes)
        : path_(path), in_(path, std::ios::binary), block_bytes_(block_bytes), block_(new char[block_bytes]) {
        if (!in_) throw InputError(fmt::format("{}: cannot open file", path));
        advise_huge_pages(block_.get(), block_bytes);
    }
    // Appends the next block to `buffer`; false when nothing was left. Starts reading the one after it.
    bool append_to(std::string& buffer) {
        if (ended_) return false;
        if (!pending_.valid()) start();
        const std::size_t got = pending_.get();  // rethrows a read error
        buffer.append(block_.get(), got);
        ended_ = in_.eof();
        if (!ended_) start();
        return got > 0;
    }
    bool ended() const { return ended_; }

private:
    void start() {
        pending_ = std::async(std::launch::async, [this] {
            in_.read(block_.get(), static_cast<std::streamsize>(block_bytes_));
            if (in_.bad()) throw InputError(fmt::format("{}: read error in file", path_));
            return static_cast<std::size_t>(in_.gcount());
        });
    }

    std::string path_;
    std::ifstream in_;
    std::size_t block_bytes_;
    std::unique_ptr<char[]> block_;
    bool ended_ = false;
    std::future<std::size_t> pending_;  // last: destroyed first, so a read still running ends before the stream
};

}  // namespace

namespace {

// The kept columns of about `rows` rows must fit in the machine's memory: refused before they are read
// (otherwise the kernel ends the process part way through a long log, with no message).
void require_memory_for_columns(const std::string& path, std::size_t rows, const CsvTable& table) {
    std::size_t kept = 0;
    for (std::size_t c = 0; c < table.header().size(); ++c) kept += table.loaded(c) ? 1 : 0;
    const double needed = static_cast<double>(rows) * static_cast<double>(kept) * sizeof(double);
    const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
    if (pages <= 0 || page <= 0) return;  // unknown: not checked
    const double memory = static_cast<double>(pages) * static_cast<double>(page);
    if (needed > memory) {
        throw InputError(fmt::format("{}: about {:.3g} rows x {} kept columns need {:.1f} GB, more than this machine's {:.1f} GB of memory; "
                                     "split the log (identify --in a.csv --in b.csv ...)",
                                     path, static_cast<double>(rows), kept, needed / 1e9, memory / 1e9));
    }
}

}  // namespace

CsvTable read_csv(const std::string& path, const CsvChunking& chunking, const CsvColumnFilter& keep) {
    const std::uintmax_t size = yaml::checked_input_file_size<InputError>(path, "file", yaml::kMaxStreamedInputFileBytes);
    BlockReader reader(path, std::max<std::size_t>(1, chunking.block_bytes));
    // At most a block and the partial line before it: reserved once, so that appending a block never
    // reallocates (and faults a fresh copy in).
    std::string buffer;
    buffer.reserve(2 * std::max<std::size_t>(1, chunking.block_bytes) + 1);
    advise_huge_pages(buffer.data(), buffer.capacity());
    auto read_more = [&] { return reader.append_to(buffer); };
    std::size_t newline = std::string::npos;
    while ((newline = buffer.find('\n')) == std::string::npos && read_more()) {
    }
    const std::size_t header_end = std::min(newline, buffer.size());
    CsvTable table(path, parse_header(std::string_view(buffer).substr(0, header_end), path));
    if (keep) table.keep_only(keep);
    buffer.erase(0, std::min(header_end + 1, buffer.size()));
    // The row count estimated from the first block's lines, so that the columns grow once.
    if (!buffer.empty() || read_more()) {
        const auto lines = static_cast<double>(std::count(buffer.begin(), buffer.end(), '\n')) + 1.0;
        const double bytes_per_line = static_cast<double>(buffer.size()) / lines;
        const auto estimate = static_cast<std::size_t>(1.02 * static_cast<double>(size) / std::max(1.0, bytes_per_line)) + 16;
        require_memory_for_columns(path, estimate, table);
        for (std::size_t c = 0; c < table.header().size(); ++c) {
            if (!table.loaded(c)) continue;
            table.mutable_column(c).reserve(estimate);
            advise_huge_pages(table.column(c));
        }
    }
    std::size_t line = 2;
    for (bool ended = reader.ended(); !buffer.empty() || !ended;) {
        if (!ended) {
            read_more();
            ended = reader.ended();
        }
        // Until the file has ended, whole lines only and never the last one (whether an empty last line is
        // the file's trailing newline or an empty line inside the data depends on what follows it).
        const std::size_t cut = ended ? buffer.size() - 1 : buffer.size() < 2 ? std::string::npos : buffer.rfind('\n', buffer.size() - 2);
        if (buffer.empty() || cut == std::string::npos) continue;  // nothing left, or no whole line yet: read on
        parse_rows(buffer, 0, cut + 1, line, ended, chunking, table);
        line += static_cast<std::size_t>(std::count(buffer.begin(), buffer.begin() + static_cast<std::ptrdiff_t>(cut + 1), '\n'));
        buffer.erase(0, cut + 1);
    }
    return table;
}


}  // namespace jacobid::io
