// SPDX-License-Identifier: MIT
#pragma once
// --log-format and its companions (--skip-bad-rows, --on-gap, --max-gap, --interpolate-max), shared by
// identify, diagnose and differentiate (docs/log-format.md). Without --log-format a log is the headered,
// uniformly sampled CSV the commands always read.
#include <string>
#include <vector>

#include "io/csv_table.hpp"
#include "io/log_format.hpp"
#include "robot/robot_description.hpp"

namespace CLI {
class App;
}

namespace jacobid::options {

struct LogFormatOptions {
    std::string file;  // --log-format; empty: a headered CSV
    std::string on_gap = "error";
    io::LogReadSettings read;
};

void add_log_format_options(CLI::App* command, LogFormatOptions& o);

// --time-tolerance (a fraction in [0, 1]) of the commands that check a log's uniform time column.
void add_time_tolerance_option(CLI::App* command, double& tolerance);

// The table of `path`: with --log-format, read and resampled with it (each skipped row and a summary on stderr, each
// irregular step too unless quiet), its columns named by `names` (q1.., qd1.., tau1.. when `names.q`
// is empty); otherwise read_csv(path).
// `period` > 0 sets the grid period (a validation log resampled like the identification log).
// --on-gap split is an InputError here (one table); commands that take segments call read_log_segments.
io::CsvTable read_log_table(const std::string& path, const LogFormatOptions& o, io::LogColumnNames names, bool quiet, double period = 0.0);

// The log of `path` as segments (read_log_table otherwise): with --on-gap split each gap and each segment
// (lines a-b, duration, samples) is printed on stderr (the segments unless quiet), and there is one table per
// segment; with the other policies, or without --log-format, the one table of read_log_table.
struct LogSegments {
    std::vector<io::CsvTable> tables;
    std::vector<io::LogSegment> segments;  // as many as tables with --log-format, empty without
    bool split = false;                    // --on-gap split was given
    double grid_period = 0.0;              // s, of every segment's grid (with --log-format)
};
// `keep`, for a plain CSV (without --log-format), the columns kept (read_csv); the formatted reader keeps only
// the columns it names anyway.
LogSegments read_log_segments(const std::string& path, const LogFormatOptions& o, io::LogColumnNames names, bool quiet, double period = 0.0,
                              const io::CsvColumnFilter& keep = {});

// For a command that reads one continuous table: "--on-gap split is not supported by COMMAND; use interpolate".
void refuse_split(const LogFormatOptions& o, const std::string& command);

// The robot description's column names (position/torque columns, qd1.. for measured velocities).
io::LogColumnNames robot_column_names(const robot::RobotDescription& robot, const std::string& time_column);

}  // namespace jacobid::options
