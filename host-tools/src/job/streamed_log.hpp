// SPDX-License-Identifier: MIT
#pragma once
// identify on a plain CSV log longer than one piece (docs/performance.md, "Ten hours"): the log is read
// piece by piece (io/csv_pieces.hpp), each piece identified and merged into the running QR factors before
// the next is read, so memory does not grow with the log. The pieces are identified as the segments of a
// log split at its gaps are (identify/pipeline/segmented_pipeline.hpp): the automatic choices (bandwidth, windows,
// decimation, torque delay, Coulomb smoothing) resolved on the first piece, the longest, and each piece
// with its own edges, so the equations within a differentiator window of each seam are not formed.
#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "identify/report/report.hpp"
#include "identify/pipeline/segmented_pipeline.hpp"
#include "io/csv_pieces.hpp"
#include "robot/robot_description.hpp"

namespace jacobid::job {

// The kept columns of one piece take at most this much (the automatic --piece-rows): with the six-axis
// pipeline's own ~140 MB, an hour of 1 kHz PUMA 560 data in one piece and ten hours in ten stay under
// 500 MB (docs/performance.md).
inline constexpr double kPieceColumnBytes = 400e6;

struct StreamedLogSettings {
    std::string path;
    io::CsvColumnFilter keep;
    std::string time_column = "t";
    double time_tolerance = 0.0;
    std::size_t piece_rows = 0;  // 0: automatic (kPieceColumnBytes)
    bool progress = false;       // a line on stderr per piece
};

// How long the pieces are: `given` rows if not 0; else as few pieces as keep each one's `kept` columns within
// kPieceColumnBytes, cut at even shares of the file's `data_bytes` (rows at most that bound).
struct PieceSize {
    std::size_t rows = 0;       // 0: no bound (one piece)
    std::uint64_t bytes = 0;    // 0: no bound
};
PieceSize piece_size_for(std::size_t estimated_rows, std::uint64_t data_bytes, std::size_t kept, std::size_t given);

class StreamedLog {
public:
    // Reads the first piece (InputError for a bad file, as read_csv).
    StreamedLog(const robot::RobotDescription& robot, StreamedLogSettings settings);
    io::CsvTable& first() { return first_; }
    // More than one piece: the file did not end with the first.
    bool several() const { return several_; }
    std::size_t estimated_rows() const { return estimated_rows_; }

    // The pieces after the first, read from the file again on each call (identify runs one method after
    // another); `first_period` is the first piece's sample period, which every piece must share. Each
    // piece read adds its line to `reports` and `names`. `release_first` is called once, before the second
    // piece is read: the caller frees the first piece there, so that one piece at a time is held.
    identify::NextSegment rest(double first_period, std::vector<identify::SegmentReport>& reports, std::vector<std::string>& names,
                               std::function<void()> release_first = {}) const;
    // The first piece read again (after release_first, for the next method).
    io::CsvTable read_first_again() const;

    // "a.csv: piece K (lines a-b)", for messages.
    static std::string piece_name(const std::string& path, std::size_t k, std::size_t first_line, std::size_t last_line);

private:
    // A reader of the file at the pieces' size, at its first piece or at `from`.
    std::unique_ptr<io::CsvPieceReader> open(const io::CsvPosition* from) const;

    const robot::RobotDescription& robot_;
    StreamedLogSettings settings_;
    io::CsvTable first_;
    io::CsvPosition after_first_;
    PieceSize size_;
    std::size_t estimated_rows_ = 0;
    bool several_ = false;
};

}  // namespace jacobid::job
