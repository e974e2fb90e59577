// SPDX-License-Identifier: MIT
#include "job/identify_inputs.hpp"

#include <fmt/core.h>

#include <cmath>
#include <exception>
#include <set>

#include "core/errors.hpp"
#include "core/parallel_for.hpp"
#include "identify/solve/estimator.hpp"
#include "io/candump_joints.hpp"
#include "io/distinct_inputs.hpp"
#if JACOBID_WITH_FIRMWARE
#include "jacobid/fwconfig/firmware_config_yaml.hpp"
#endif

namespace jacobid::job {

using namespace jacobid::options;

namespace {

// The columns of a plain CSV that identify reads (identify::log_columns): time, positions and torques, the
// measured velocities qdJ with --velocity measured, the references q_refJ / qd_refJ with --estimator iv|didim.
io::CsvColumnFilter identify_columns(const io::LogColumnNames& names, const IdentifyOptions& o) {
    std::set<std::string> kept = {names.time};
    kept.insert(names.q.begin(), names.q.end());
    kept.insert(names.tau.begin(), names.tau.end());
    if (o.velocity == "measured") kept.insert(names.qd.begin(), names.qd.end());
    if (o.estimator == "iv" || o.estimator == "didim") {
        for (std::size_t j = 0; j < names.q.size(); ++j) {
            for (const std::string& column : identify::reference_column_names(j)) kept.insert(column);
        }
    }
    return [kept = std::move(kept)](const std::string& name) { return kept.count(name) != 0; };
}


// One plain CSV log that a least-squares estimator identifies: read piece by piece when it is longer than a
// piece (job/streamed_log.hpp). The estimators that simulate the log (iv, didim) and --period need it whole.
bool streamable(const std::vector<LogSource>& sources, const IdentifyOptions& o) {
    const LogFormatOptions& f = o.log_format;
    return sources.size() == 1 && !sources.front().table && f.file.empty() && !f.read.skip_bad_rows && f.on_gap == "error" && !(f.read.max_gap > 0.0) &&
           o.can_config.empty() && o.period.empty() && o.estimator != "iv" && o.estimator != "didim";
}

}  // namespace

std::string log_names(const std::vector<std::string>& inputs) {
    std::string names;
    for (const std::string& in : inputs) names += (names.empty() ? "" : " + ") + in;
    return names;
}


// A CSV log (with --on-gap split, one table per segment), or with --can-config a candump capture decoded by
// the firmware's joint profiles; a table given as it is.
LogSegments read_log(LogSource source, const robot::RobotDescription& robot, const IdentifyOptions& o, double period) {
    if (source.table) {
        LogSegments given;
        given.tables.push_back(std::move(*source.table));
        return given;
    }
    const std::string& path = source.name;
    if (o.can_config.empty()) {
        const io::LogColumnNames names = robot_column_names(robot, o.time_column);
        return read_log_segments(path, o.log_format, names, o.quiet, period, identify_columns(names, o));
    }
    if (!o.log_format.file.empty()) throw InputError("--log-format and --can-config: give one of them");
#if JACOBID_WITH_FIRMWARE
    firmware::FirmwareConfig fw;
    try {
        fw = firmware::load_firmware_config(o.can_config);
    } catch (const firmware::ConfigError& e) {
        throw InputError(fmt::format("--can-config {}", e.what()));
    }
    if (fw.joints.size() != robot.joints.size()) {
        throw InputError(fmt::format("--can-config {}: {} joints, but the robot description has {}", o.can_config, fw.joints.size(),
                                     robot.joints.size()));
    }
    std::vector<hal::ProfileConfig> decoders;
    for (const auto& joint : fw.joints) decoders.push_back(joint.decoder);
    const io::LogColumnNames names = robot_column_names(robot, o.time_column);
    io::CandumpJointCounts counts;
    LogSegments table;
    table.tables.push_back(io::candump_joint_table(io::read_candump_log(path), decoders, names.q, names.tau, o.time_column, path, &counts));
    if (!o.quiet) {
        fmt::print(stderr, "{}: {} samples from {} decoded frames ({} frames of other ids and {} error frames skipped){}\n", path, counts.samples,
                   counts.frames_decoded, counts.frames_other_ids, counts.error_frames,
                   counts.regridded ? fmt::format("; time stamps within +-{:.3g} ms of a {:.6g} ms cycle (receive-time jitter): the nominal cycle used",
                                                  1e3 * counts.max_jitter, 1e3 * counts.cycle)
                                    : std::string());
    }
    return table;
#else
    (void)robot;
    throw InputError(fmt::format("--can-config: this jacobid was built without the HAL/firmware (JACOBID_BUILD_HAL=OFF), cannot decode {}", path));
#endif
}


std::vector<identify::LogColumns> columns_of(const LogSegments& logs, const robot::RobotDescription& robot, const IdentifyOptions& o) {
    std::vector<identify::LogColumns> columns;
    const double grid_period = logs.split ? logs.grid_period : 0.0;
    for (const auto& table : logs.tables) columns.push_back(identify::log_columns(table, robot, o.time_column, o.time_tolerance, grid_period));
    return columns;
}

std::vector<identify::SegmentReport> segment_reports(const std::vector<io::LogSegment>& segments, const std::vector<bool>& used,
                                                     const std::vector<std::string>& why, const char* method, const std::string& path) {
    std::vector<identify::SegmentReport> reports;
    for (std::size_t s = 0; s < segments.size(); ++s) {
        const io::LogSegment& g = segments[s];
        reports.push_back({g.first_line, g.last_line, g.duration, g.samples, used[s], why[s], 0, ""});
        if (!used[s]) fmt::print(stderr, "jacobid identify [{}]: {}: segment {} ({}) not used: {}\n", method, path, s + 1, g.describe(), why[s]);
    }
    return reports;
}


void check_sample_period(const std::string& log, double period, const std::string& first, double first_period) {
    if (std::abs(period - first_period) <= 1e-3 * first_period) return;
    throw InputError(fmt::format("--in {}: sampled every {:.6g} ms, but --in {} every {:.6g} ms; logs identified together must share "
                                 "their sample period (resample one of them)",
                                 log, 1e3 * period, first, 1e3 * first_period));
}

InputLogs read_inputs(std::vector<LogSource> sources, const robot::RobotDescription& robot, const IdentifyOptions& o, double grid_period) {
    std::vector<std::string> files;
    for (const LogSource& s : sources) {
        if (!s.table) files.push_back(s.name);
    }
    io::require_distinct_inputs("--in", files);  // one log twice (a link, a copy) would count its equations twice
    InputLogs in;
    in.read.resize(o.inputs.size());
    if (streamable(sources, o)) {
        const io::LogColumnNames names = robot_column_names(robot, o.time_column);
        in.streamed = std::make_unique<StreamedLog>(
            robot, StreamedLogSettings{o.first_input(), identify_columns(names, o), o.time_column, o.time_tolerance, o.piece_rows, !o.quiet});
        in.read[0].tables.push_back(std::move(in.streamed->first()));
    } else if (o.piece_rows > 0) {
        throw InputError("--piece-rows: only a plain CSV log (one --in, without --log-format or --can-config) identified by least squares "
                         "(not --estimator iv|didim or --period) is read in pieces");
    }
    ParallelForOptions pool;
    pool.threads = o.threads;
    // Raw logs (--log-format) are resampled onto one grid, the first log's, so that one plan serves them all
    // (each on its own mean step, the UR10e's Fourier runs differ by up to 2 % and were refused).
    const bool one_grid = !o.log_format.file.empty() && o.inputs.size() > 1;
    if (one_grid) in.read[0] = read_log(std::move(sources[0]), robot, o);
    const double period = one_grid ? in.read[0].grid_period : grid_period;
    const std::vector<std::exception_ptr> errors = parallel_for(o.inputs.size(), pool, [&](std::size_t k) {
        if (!(one_grid && k == 0) && !in.streamed) in.read[k] = read_log(std::move(sources[k]), robot, o, period);
    });
    for (const auto& e : errors) {
        if (e) std::rethrow_exception(e);  // the first --in that failed, whatever the threads
    }
    for (std::size_t k = 0; k < in.read.size(); ++k) {
        const LogSegments& logs = in.read[k];
        std::vector<identify::LogColumns> columns = columns_of(logs, robot, o);
        // The time stamps have given each piece its period and start: nothing reads them again.
        for (io::CsvTable& table : in.read[k].tables) table.release(o.time_column);
        for (std::size_t s = 0; s < columns.size(); ++s) {
            identify::SegmentReport piece;
            if (in.several()) piece.log = o.inputs[k];
            piece.samples = columns[s].samples();
            piece.duration = piece.samples > 1 ? static_cast<double>(piece.samples - 1) * columns[s].sample_period : 0.0;
            std::string name = o.inputs[k];
            if (in.in_pieces()) {
                const io::CsvTable& table = logs.tables[s];
                piece.first_line = table.line_of_row(0);
                piece.last_line = table.line_of_row(table.rows() - 1);
                piece.log = o.inputs[k];  // each piece on its own line of the report, with its equations
                name = StreamedLog::piece_name(o.inputs[k], 1, piece.first_line, piece.last_line);
            }
            if (s < logs.segments.size() && logs.split) {
                piece.first_line = logs.segments[s].first_line;
                piece.last_line = logs.segments[s].last_line;
                piece.duration = logs.segments[s].duration;
                name += fmt::format(": segment {} ({})", s + 1, logs.segments[s].describe());
            }
            // One plan (windows, F_p, decimation in samples) serves every piece: the logs must share their sampling.
            if (!in.columns.empty()) check_sample_period(o.inputs[k], columns[s].sample_period, o.inputs.front(), in.columns.front().sample_period);
            // A given --cutoff is refused above the Nyquist frequency (as differentiate does), not clamped to
            // the shortest windows: the settings line would name another cutoff than the one asked for.
            const double nyquist = 0.5 / columns[s].sample_period;
            if (o.pipeline.differentiator_cutoff >= nyquist) {
                throw InputError(fmt::format("--cutoff {:g} Hz: must be below the Nyquist frequency {:g} Hz of --in {} (sample period {:g} s)",
                                             o.pipeline.differentiator_cutoff, nyquist, o.inputs[k], columns[s].sample_period));
            }
            in.pieces.push_back(piece);
            in.names.push_back(name);
            in.columns.push_back(std::move(columns[s]));
        }
    }
    return in;
}


void release_first_piece(InputLogs& in) {
    in.columns.front() = identify::LogColumns{};
    std::vector<io::CsvTable>().swap(in.read.front().tables);
}

void read_first_piece_again(InputLogs& in, const robot::RobotDescription& robot, const IdentifyOptions& o) {
    std::vector<io::CsvTable>& tables = in.read.front().tables;
    tables.push_back(in.streamed->read_first_again());
    in.columns.front() = identify::log_columns(tables.front(), robot, o.time_column, o.time_tolerance, 0.0);
    tables.front().release(o.time_column);
}

std::vector<identify::SegmentReport> piece_reports(std::vector<identify::SegmentReport> reports, const std::vector<std::string>& names,
                                                   const identify::SegmentedOutput& split, const char* method) {
    for (std::size_t s = 0; s < reports.size(); ++s) {
        identify::SegmentReport& r = reports[s];
        r.used = split.used[s];
        r.why = split.why[s];
        r.rows = split.rows[s];
        if (!r.used) fmt::print(stderr, "jacobid identify [{}]: {} not used: {}\n", method, names[s], r.why);
    }
    return reports;
}


}  // namespace jacobid::job
