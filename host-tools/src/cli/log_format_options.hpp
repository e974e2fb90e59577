// SPDX-License-Identifier: MIT
#pragma once
// --log-format and its companions (--skip-bad-rows, --on-gap, --max-gap, --interpolate-max), shared by
// identify, diagnose and differentiate (docs/log-format.md). Without --log-format a log is the headered,
// uniformly sampled CSV the commands always read.
#include <string>

#include "io/csv_table.hpp"
#include "io/log_format.hpp"
#include "robot/robot_description.hpp"

namespace CLI {
class App;
}

namespace jacobid::cli {

struct LogFormatOptions {
    std::string file;  // --log-format; empty: a headered CSV
    std::string on_gap = "error";
    io::LogReadSettings read;
};

void add_log_format_options(CLI::App* command, LogFormatOptions& o);

// The table of `path`: with --log-format, read and resampled with it (each skipped row and a summary on stderr, each
// irregular step too unless quiet), its columns named by `names` (q1.., qd1.., tau1.. when `names.q`
// is empty); otherwise read_csv(path).
// `period` > 0 sets the grid period (a validation log resampled like the identification log).
io::CsvTable read_log_table(const std::string& path, const LogFormatOptions& o, io::LogColumnNames names, bool quiet, double period = 0.0);

// The robot description's column names (position/torque columns, qd1.. for measured velocities).
io::LogColumnNames robot_column_names(const robot::RobotDescription& robot, const std::string& time_column);

}  // namespace jacobid::cli
