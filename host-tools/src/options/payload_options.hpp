// SPDX-License-Identifier: MIT
#pragma once
// jacobid payload's options and run, shared by the command (cli/payload_command.cpp) and the Python module's
// jacobid.payload (python/src/payload_bindings.cpp): the same checks, the same messages.
#include <string>
#include <vector>

#include "options/fit_options.hpp"
#include "options/log_format_options.hpp"
#include "io/time_axis.hpp"
#include "payload/arm_file.hpp"
#include "payload/payload_estimate.hpp"

namespace CLI {
class App;
class Option;
}  // namespace CLI

namespace jacobid::options {

struct PayloadOptions {
    std::string robot, arm, in, unloaded;  // files: the command's own options (the Python function's arguments)
    std::string frame;
    std::vector<double> tool_frame, gain_std;
    double mass = 0.0;
    const CLI::Option* mass_option = nullptr;  // whether --mass was given
    std::string time_column = "t";
    double time_tolerance = io::kDefaultTimeTolerance;
    bool quiet = false;
    LogFormatOptions log_format;
    FitOptions fit;
};

// --frame, --tool-frame, --mass, --gain-std, --time-column, --time-tolerance, the log format's and fit options.
void add_payload_options(CLI::App* command, PayloadOptions& o);

struct PayloadRun {
    robot::RobotDescription robot;
    payload::ArmModel arm;
    payload::PayloadEstimate estimate;
};

// Reads the robot, the arm and the logs and estimates the payload. InputError for bad input (naming the file,
// line, column or option).
PayloadRun run_payload(const PayloadOptions& o);

}  // namespace jacobid::options
