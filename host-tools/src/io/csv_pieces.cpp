// SPDX-License-Identifier: MIT
#include "io/csv_pieces.hpp"

#include <fmt/core.h>

#include <unistd.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <future>
#include <limits>

#include "core/errors.hpp"
#include "core/huge_pages.hpp"
#include "io/csv_rows.hpp"
#include "jacobid/yaml/input_file.hpp"

namespace jacobid::io {

// The file block by block from an offset, each next block read on a second thread while the caller parses
// the last one: reading (a copy out of the page cache, 0.35 s for an hour's 1.4 GB) no longer waits for the
// parse. The block is never zero-filled (a std::string resized by a block was: 0.3 s of memset per hour).
class CsvPieceReader::Blocks {
public:
    Blocks(const std::string& path, std::size_t block_bytes, std::uint64_t offset)
        : path_(path), in_(path, std::ios::binary), block_bytes_(block_bytes), block_(new char[block_bytes]) {
        if (!in_) throw InputError(fmt::format("{}: cannot open file", path));
        if (offset > 0 && !in_.seekg(static_cast<std::streamoff>(offset))) throw InputError(fmt::format("{}: cannot seek to byte {}", path, offset));
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

namespace {

// The kept columns of about `rows` rows must fit in the machine's memory: refused before they are read
// (otherwise the kernel ends the process part way through a long log, with no message).
void require_memory_for_columns(const std::string& path, std::size_t rows, std::size_t kept) {
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

// Offset one past the n-th '\n' of text[0, end), or npos when it holds fewer.
std::size_t after_nth_newline(const std::string& text, std::size_t end, std::size_t n) {
    const char* p = text.data();
    const char* stop = text.data() + end;
    for (std::size_t k = 0; k < n; ++k) {
        p = static_cast<const char*>(std::memchr(p, '\n', static_cast<std::size_t>(stop - p)));
        if (p == nullptr) return std::string::npos;
        ++p;
    }
    return static_cast<std::size_t>(p - text.data());
}

}  // namespace

CsvPieceReader::CsvPieceReader(const std::string& path, const CsvChunking& chunking, const CsvColumnFilter& keep, const CsvPosition* from)
    : path_(path), chunking_(chunking) {
    chunking_.block_bytes = std::max<std::size_t>(1, chunking_.block_bytes);
    size_ = yaml::checked_input_file_size<InputError>(path, "file", yaml::kMaxStreamedInputFileBytes);
    blocks_ = std::make_unique<Blocks>(path, chunking_.block_bytes, 0);
    // At most a block and the partial line before it: reserved once, so that appending a block never
    // reallocates (and faults a fresh copy in).
    buffer_.reserve(2 * chunking_.block_bytes + 1);
    advise_huge_pages(buffer_.data(), buffer_.capacity());
    std::size_t newline = std::string::npos;
    while ((newline = buffer_.find('\n')) == std::string::npos && read_more()) {
    }
    const std::size_t header_end = std::min(newline, buffer_.size());
    columns_ = CsvTable(path, parse_csv_header(std::string_view(buffer_).substr(0, header_end), path));
    if (keep) {
        // A header with none of the wanted names (a binary or foreign file read as one odd column) was a
        // logic_error inside keep_only: "internal error ... told to keep none of its 1 columns", exit 3.
        const std::vector<std::string>& names = columns_.header();
        if (std::none_of(names.begin(), names.end(), keep)) {
            throw InputError(fmt::format("{}:1: none of the header's columns ({}) is one this command reads", path, describe_columns(names)));
        }
        columns_.keep_only(keep);
    }
    const std::size_t data_start = std::min(header_end + 1, buffer_.size());
    data_bytes_ = size_ - std::min<std::uint64_t>(size_, data_start);
    if (from != nullptr) {
        buffer_.clear();
        blocks_ = std::make_unique<Blocks>(path, chunking_.block_bytes, from->offset);
        consumed_ = from->offset;
        line_ = from->line;
        carried_ = from->carried;
        carried_line_ = from->carried_line;
        first_ = false;
    } else {
        buffer_.erase(0, data_start);
        consumed_ = data_start;
    }
    // The row count estimated from the first block's lines, so that the columns grow once.
    if (!buffer_.empty() || read_more()) {
        const auto lines = static_cast<double>(std::count(buffer_.begin(), buffer_.end(), '\n')) + 1.0;
        bytes_per_line_ = std::max(1.0, static_cast<double>(buffer_.size()) / lines);
        estimated_rows_ = rows_in(size_ - consumed_);
    }
}

CsvPieceReader::~CsvPieceReader() = default;

std::size_t CsvPieceReader::kept_columns() const {
    std::size_t kept = 0;
    for (std::size_t c = 0; c < columns_.header().size(); ++c) kept += columns_.loaded(c) ? 1 : 0;
    return kept;
}

bool CsvPieceReader::read_more() { return blocks_->append_to(buffer_); }

CsvPosition CsvPieceReader::position() const { return {consumed_, line_, carried_, carried_line_}; }

bool CsvPieceReader::at_end() const { return buffer_.empty() && blocks_->ended(); }

std::size_t CsvPieceReader::rows_in(std::uint64_t bytes) const {
    return static_cast<std::size_t>(1.02 * static_cast<double>(bytes) / bytes_per_line_) + 16;
}

bool CsvPieceReader::next(CsvTable& piece) {
    const bool first = first_;
    first_ = false;
    if (!first && at_end()) return false;
    std::size_t cap = piece_rows_ > 0 ? piece_rows_ : std::numeric_limits<std::size_t>::max();
    std::size_t expected = std::min(rows_in(size_ - consumed_) + carried_.size(), cap);
    if (piece_bytes_ > 0) expected = std::min(expected, rows_in(piece_bytes_) + 1);
    require_memory_for_columns(path_, expected, kept_columns());
    piece = columns_;
    piece.set_first_line(carried_.empty() ? line_ : carried_line_);
    for (std::size_t c = 0, k = 0; c < piece.header().size(); ++c) {
        if (!piece.loaded(c)) continue;
        std::vector<double>& column = piece.mutable_column(c);
        column.reserve(expected);
        advise_huge_pages(column);
        if (!carried_.empty()) column.push_back(carried_[k++]);
    }
    const std::size_t carried_rows = carried_.empty() ? 0 : 1;
    const std::uint64_t piece_start = consumed_;
    for (;;) {
        if (piece.rows() >= cap) {
            // A short rest of the file stays in this piece rather than becoming a sliver of its own.
            if ((size_ - consumed_) * 20 >= consumed_ - piece_start) break;
            cap = std::numeric_limits<std::size_t>::max();
        }
        const bool ended = blocks_->ended();
        if (buffer_.empty() && ended) break;
        // Until the file has ended, whole lines only and never the last one (whether an empty last line is
        // the file's trailing newline or an empty line inside the data depends on what follows it).
        std::size_t cut = ended ? buffer_.size() - 1 : buffer_.size() < 2 ? std::string::npos : buffer_.rfind('\n', buffer_.size() - 2);
        if (buffer_.empty() || cut == std::string::npos) {
            read_more();  // nothing left, or no whole line yet: read on
            continue;
        }
        // At most the rows this piece still takes, and the line that crosses its byte bound.
        const std::size_t limit = after_nth_newline(buffer_, cut + 1, cap - piece.rows());
        if (limit != std::string::npos) cut = std::min(cut, limit - 1);
        if (piece_bytes_ > 0 && cap != std::numeric_limits<std::size_t>::max()) {
            const std::uint64_t taken = consumed_ - piece_start;
            if (taken >= piece_bytes_) {
                cap = piece.rows();  // full: the check above ends it (or takes a short rest in)
                continue;
            }
            const std::size_t crossing = buffer_.find('\n', static_cast<std::size_t>(piece_bytes_ - taken - 1));
            if (crossing != std::string::npos) cut = std::min(cut, crossing);
        }
        const bool last = ended && cut + 1 == buffer_.size();
        parse_csv_rows(buffer_, 0, cut + 1, line_, last, chunking_, piece);
        line_ += static_cast<std::size_t>(std::count(buffer_.begin(), buffer_.begin() + static_cast<std::ptrdiff_t>(cut + 1), '\n'));
        consumed_ += cut + 1;
        buffer_.erase(0, cut + 1);
    }
    if (!first && piece.rows() <= carried_rows) return false;
    carried_.clear();
    if (piece.rows() > 0) {
        for (std::size_t c = 0; c < piece.header().size(); ++c) {
            if (piece.loaded(c)) carried_.push_back(piece.column(c).back());
        }
        carried_line_ = piece.line_of_row(piece.rows() - 1);
    }
    return true;
}

CsvTable read_csv(const std::string& path, const CsvChunking& chunking, const CsvColumnFilter& keep) {
    CsvPieceReader reader(path, chunking, keep);
    CsvTable table;
    reader.next(table);
    return table;
}

}  // namespace jacobid::io
