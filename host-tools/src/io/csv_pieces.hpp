// SPDX-License-Identifier: MIT
#pragma once
// A CSV log read piece by piece, so that a log of any length is identified in the memory of one piece
// (identify; docs/performance.md, "Ten hours"). The file is streamed in blocks of whole lines, as read_csv
// reads it (read_csv is the one-piece case), each block parsed as it arrives. Consecutive pieces share one
// row: the last row of a piece is the first of the next, so that every time step of the file lies inside a
// piece and its uniform-time check sees it. Every problem is an InputError naming the file and line.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "io/csv_table.hpp"

namespace jacobid::io {

// Where a piece starts in the file: a later reader resumes there (identify runs one method after another).
struct CsvPosition {
    std::uint64_t offset = 0;     // byte of its first new line
    std::size_t line = 2;         // that line's number
    std::vector<double> carried;  // the previous piece's last row (its kept columns), empty before the first piece
    std::size_t carried_line = 0;
};

class CsvPieceReader {
public:
    // Opens `path` and reads its header; `from` resumes at a position() of an earlier reader of the same file.
    CsvPieceReader(const std::string& path, const CsvChunking& chunking = {}, const CsvColumnFilter& keep = {}, const CsvPosition* from = nullptr);
    ~CsvPieceReader();
    CsvPieceReader(const CsvPieceReader&) = delete;
    CsvPieceReader& operator=(const CsvPieceReader&) = delete;

    // Rows of the file, estimated from the first block's line length (within a few %), and the kept columns:
    // what a caller sizes its pieces by.
    std::size_t estimated_rows() const { return estimated_rows_; }
    std::size_t kept_columns() const;
    std::uint64_t data_bytes() const { return data_bytes_; }  // of the rows: the file after its header
    // At most `rows` rows per piece (0, the default: the whole file in one piece). A piece that would leave
    // less than a twentieth of itself in the file takes the rest too (no sliver of a piece at the end).
    void set_piece_rows(std::size_t rows) { piece_rows_ = rows; }
    // Also at most about `bytes` of the file per piece (0, the default: no bound), ending at the line that
    // crosses it: pieces of even length whatever the lines' length does along the file.
    void set_piece_bytes(std::uint64_t bytes) { piece_bytes_ = bytes; }

    // The next piece into `piece`; false when no row is left. The first call always returns the (first)
    // table, empty for a file of a header only. InputError when the kept columns of the piece cannot fit
    // in the machine's memory, before they are read.
    bool next(CsvTable& piece);
    // Where the next piece starts, and whether the file has no row left.
    CsvPosition position() const;
    bool at_end() const;

private:
    class Blocks;
    bool read_more();
    // Rows in `bytes` of the file by the first block's line length, 2 % and 16 rows over: what columns reserve.
    std::size_t rows_in(std::uint64_t bytes) const;

    std::string path_;
    CsvChunking chunking_;
    std::uint64_t size_ = 0;
    std::unique_ptr<Blocks> blocks_;
    std::string buffer_;          // whole lines not parsed yet, then a partial line
    std::uint64_t consumed_ = 0;  // file offset of buffer_[0]
    std::size_t line_ = 2;        // line number of buffer_[0]
    CsvTable columns_;            // header and kept columns, no rows: every piece starts as a copy
    std::size_t estimated_rows_ = 0;
    double bytes_per_line_ = 1.0;
    std::size_t piece_rows_ = 0;
    std::uint64_t piece_bytes_ = 0;
    std::uint64_t data_bytes_ = 0;
    bool first_ = true;
    std::vector<double> carried_;
    std::size_t carried_line_ = 0;
};

}  // namespace jacobid::io
