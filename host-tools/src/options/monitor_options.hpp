// SPDX-License-Identifier: MIT
#pragma once
// The options and the runs of `jacobid monitor` and `jacobid monitor calibrate` (docs/monitor.md), shared by
// the command line (monitor_command.cpp) and the Python module (python/src/monitor_bindings.cpp), so that
// both check the same options with the same words and compute the same results.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "options/log_format_options.hpp"
#include "io/time_axis.hpp"
#include "monitor/monitor_file.hpp"

namespace CLI {
class App;
}

namespace jacobid::options {

// What both forms read: the robot, the logs and how they are laid out.
struct MonitorInputs {
    std::string robot;
    std::vector<std::string> logs;
    std::string time_column = "t";
    double time_tolerance = io::kDefaultTimeTolerance;
    LogFormatOptions log_format;
};

struct MonitorCalibrateOptions : MonitorInputs {
    std::string out;
    std::string estimator = "observer";
    monitor::MonitorFile file;
};

struct MonitorReplayOptions : MonitorInputs {
    std::string monitor;
    std::string plot;
    std::string estimates;
};

// --time-column, --time-tolerance and the log format's options (not --robot and --in: the command line adds
// those, the Python functions take them as arguments).
void add_monitor_log_options(CLI::App* cmd, MonitorInputs& o);
// calibrate's own: --out, --false-alarm-rate, --margin, --estimator, --gain, the windows, --xi, --standing-*,
// --band-margin, --confirm, --hold, --no-measured-velocity.
void add_monitor_calibrate_options(CLI::App* cmd, MonitorCalibrateOptions& o);
// monitor's own: --plot, --estimates (not --monitor: an argument of the Python function).
void add_monitor_replay_options(CLI::App* cmd, MonitorReplayOptions& o);

struct MonitorRun {
    nlohmann::json json;
    std::string text;
};
// Calibrates and writes o.out; InputError for bad input, naming the file, line or option.
MonitorRun run_monitor_calibrate(MonitorCalibrateOptions o);
// Replays the one log and writes --plot and --estimates when given.
MonitorRun run_monitor_replay(const MonitorReplayOptions& o);

}  // namespace jacobid::options
