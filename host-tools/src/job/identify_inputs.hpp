// SPDX-License-Identifier: MIT
#pragma once
// The logs of an identification, read as `--in` reads them: CSV files (whole, in pieces when long, or cut at
// their gaps with --on-gap split), raw logs through --log-format, candump captures through --can-config, or
// tables already in memory (the Python module's arrays). Several logs are read on up to --threads threads,
// in --in order whatever the threads; every piece gets its report line and its name for messages.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "identify/plan/log_columns.hpp"
#include "identify/report/report.hpp"
#include "identify/pipeline/segmented_pipeline.hpp"
#include "io/csv_table.hpp"
#include "job/streamed_log.hpp"
#include "options/identify_options.hpp"
#include "options/log_format_options.hpp"
#include "robot/robot_description.hpp"

namespace jacobid::job {

// One log: the file `name`, or `table` when given (its name is then only for messages).
struct LogSource {
    std::string name;
    std::optional<io::CsvTable> table;
};

// A log of `o.inputs` (or --validate) read into segments: one table, or one per segment with --on-gap split.
// `period` (s, > 0): a raw log (--log-format) is resampled onto that grid instead of its own mean step.
options::LogSegments read_log(LogSource source, const robot::RobotDescription& robot, const options::IdentifyOptions& o, double period = 0.0);

// The joints' columns of each table (one, or one per segment with --on-gap split).
std::vector<identify::LogColumns> columns_of(const options::LogSegments& logs, const robot::RobotDescription& robot,
                                             const options::IdentifyOptions& o);

// The logs of --in and their columns: one per log, or one per segment with --on-gap split; `pieces` says
// where each comes from.
struct InputLogs {
    std::vector<options::LogSegments> read;         // per --in
    std::vector<identify::LogColumns> columns;      // every log's, or every segment's, in --in order
    std::vector<identify::SegmentReport> pieces;    // per entry of `columns`: log path (several logs), lines, duration, samples
    std::vector<std::string> names;                 // per entry of `columns`, for messages: "a.csv", "a.csv: segment 2 (lines ...)"
    std::unique_ptr<StreamedLog> streamed;          // one CSV log read piece by piece: `columns` holds its first piece
    bool several() const { return read.size() > 1; }
    bool split() const { return !read.empty() && read.front().split; }
    bool in_pieces() const { return streamed && streamed->several(); }
};

// `sources`: one per o.inputs, in order. InputError for a bad file, logs of different sample periods, a
// --cutoff above a log's Nyquist frequency, --piece-rows where a log cannot be read in pieces. `grid_period`
// (s, > 0): a single raw log is resampled onto that grid (a fleet's log onto its plan's, as the first --in's
// grid serves every raw log of one identify).
InputLogs read_inputs(std::vector<LogSource> sources, const robot::RobotDescription& robot, const options::IdentifyOptions& o,
                      double grid_period = 0.0);

// InputError unless `log`'s sample period (s) is `first`'s, as logs identified together must share it.
void check_sample_period(const std::string& log, double period, const std::string& first, double first_period);

// A log read piece by piece: its first piece freed once identified, so that one piece at a time is held, and
// read again for the next method.
void release_first_piece(InputLogs& in);
void read_first_piece_again(InputLogs& in, const robot::RobotDescription& robot, const options::IdentifyOptions& o);

// The report lines of the pieces (segments and/or logs): `reports` and `names` those read in advance, then
// those read piece by piece; each piece not used also on stderr (never dropped silently).
std::vector<identify::SegmentReport> piece_reports(std::vector<identify::SegmentReport> reports, const std::vector<std::string>& names,
                                                   const identify::SegmentedOutput& split, const char* method);

// The segments' report lines, each segment not used also on stderr.
std::vector<identify::SegmentReport> segment_reports(const std::vector<io::LogSegment>& segments, const std::vector<bool>& used,
                                                     const std::vector<std::string>& why, const char* method, const std::string& path);

// "a.csv", or "a.csv + b.csv" for several logs (titles, messages, the JSON's "log").
std::string log_names(const std::vector<std::string>& inputs);

}  // namespace jacobid::job
