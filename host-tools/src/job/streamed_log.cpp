// SPDX-License-Identifier: MIT
#include "job/streamed_log.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>

#include "core/errors.hpp"
#include "identify/plan/log_columns.hpp"

namespace jacobid::job {

PieceSize piece_size_for(std::size_t estimated_rows, std::uint64_t data_bytes, std::size_t kept, std::size_t given) {
    if (given > 0) return {given, 0};
    const auto largest = std::max<std::size_t>(2, static_cast<std::size_t>(kPieceColumnBytes / (8.0 * static_cast<double>(std::max<std::size_t>(1, kept)))));
    const std::size_t pieces = (estimated_rows + largest - 1) / largest;
    if (pieces <= 1) return {largest, 0};
    // The estimate is from the first block's lines (a few % off where the lines grow longer): even shares of
    // the bytes give even pieces whatever the lines do.
    return {largest, (data_bytes + pieces - 1) / pieces};
}

std::string StreamedLog::piece_name(const std::string& path, std::size_t k, std::size_t first_line, std::size_t last_line) {
    return fmt::format("{}: piece {} (lines {}-{})", path, k, first_line, last_line);
}

StreamedLog::StreamedLog(const robot::RobotDescription& robot, StreamedLogSettings settings) : robot_(robot), settings_(std::move(settings)) {
    io::CsvPieceReader reader(settings_.path, {}, settings_.keep);
    estimated_rows_ = reader.estimated_rows();
    size_ = piece_size_for(estimated_rows_, reader.data_bytes(), reader.kept_columns(), settings_.piece_rows);
    reader.set_piece_rows(size_.rows);
    reader.set_piece_bytes(size_.bytes);
    reader.next(first_);
    several_ = !reader.at_end();
    after_first_ = reader.position();
}

std::unique_ptr<io::CsvPieceReader> StreamedLog::open(const io::CsvPosition* from) const {
    auto reader = std::make_unique<io::CsvPieceReader>(settings_.path, io::CsvChunking{}, settings_.keep, from);
    reader->set_piece_rows(size_.rows);
    reader->set_piece_bytes(size_.bytes);
    return reader;
}

io::CsvTable StreamedLog::read_first_again() const {
    io::CsvTable table;
    open(nullptr)->next(table);
    return table;
}

identify::NextSegment StreamedLog::rest(double first_period, std::vector<identify::SegmentReport>& reports, std::vector<std::string>& names,
                                        std::function<void()> release_first) const {
    if (!several_) return {};
    // Shared by the copies of the returned function; the table of the piece last returned lives here.
    struct State {
        io::CsvPosition next;
        io::CsvTable table;
        std::size_t index = 1;
        std::function<void()> release_first;
    };
    auto state = std::make_shared<State>();
    state->release_first = std::move(release_first);
    state->next = after_first_;
    return [this, state, first_period, &reports, &names](identify::LogColumns& piece) {
        // The last piece is identified; the next is read into its columns' storage, not into fresh memory:
        // nothing more is held, and the 350 MB of a piece are not faulted in and zeroed by the kernel again
        // (three hours in three pieces: 102 000 -> 95 700 minor faults).
        if (state->release_first) {
            state->release_first();
            state->release_first = nullptr;
        }
        {
            // A reader lives only while it reads a piece: its block, the read ahead and the partial lines
            // (32-48 MB) are not held beside a piece while it is identified (the later pieces of ten hours: 489 -> 442 MB).
            const std::unique_ptr<io::CsvPieceReader> reader = open(&state->next);
            if (!reader->next(state->table)) return false;
            state->next = reader->position();
        }
        ++state->index;
        const io::CsvTable& table = state->table;
        const std::size_t first_line = table.line_of_row(0), last_line = table.line_of_row(table.rows() - 1);
        const std::string name = piece_name(settings_.path, state->index, first_line, last_line);
        piece = identify::log_columns(table, robot_, settings_.time_column, settings_.time_tolerance, 0.0);
        state->table.release(settings_.time_column);
        // Identified once (read again for a further method): its torques are aligned in place, not copied.
        piece.own_tau = identify::writable_torques(state->table, piece);
        // One plan (windows, F_p, decimation in samples) serves every piece: they must share their sampling.
        if (std::abs(piece.sample_period - first_period) > 1e-3 * first_period) {
            throw InputError(fmt::format("{}: sampled every {:.6g} ms, but the first piece every {:.6g} ms; a log's sample period must not change",
                                         name, 1e3 * piece.sample_period, 1e3 * first_period));
        }
        identify::SegmentReport report;
        report.log = settings_.path;  // each piece on its own line of the report, with its equations
        report.first_line = first_line;
        report.last_line = last_line;
        report.samples = piece.samples();
        report.duration = report.samples > 1 ? static_cast<double>(report.samples - 1) * piece.sample_period : 0.0;
        reports.push_back(report);
        names.push_back(name);
        if (settings_.progress) fmt::print(stderr, "identify: {}: {} rows read\n", name, table.rows());
        return true;
    };
}

}  // namespace jacobid::job
