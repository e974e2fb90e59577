// SPDX-License-Identifier: MIT
#pragma once
// identify --drive-gains --loaded LOG --payload-mass KG [--payload-com x,y,z] [--payload-inertia ...]: the
// options and the run (identify/drive_gains/drive_gains.hpp), kept out of identify_command.cpp.
#include <string>
#include <utility>
#include <vector>

#include "options/fit_options.hpp"
#include "options/log_format_options.hpp"
#include "robot/robot_description.hpp"
#include "robot/robot_model.hpp"

namespace CLI {
class App;
class Option;
}

namespace jacobid::options {

struct DriveGainOptions {
    bool enabled = false;  // --drive-gains
    std::string loaded;    // --loaded
    double payload_mass = 0.0;
    const CLI::Option* payload_mass_option = nullptr;  // whether --payload-mass was given (its count)
    std::vector<double> payload_com;      // 3 values, m
    std::vector<double> payload_inertia;  // 6 values, kg.m^2
};

void add_drive_gain_options(CLI::App* command, DriveGainOptions& o);

// Where identify reads its logs and what it prints.
struct DriveGainInputs {
    std::string in, format, time_column;
    double time_tolerance = 0.0;
    bool quiet = false;
    const LogFormatOptions* log_format = nullptr;
    // identify's options that --drive-gains does not use, and whether each was given (refused then).
    std::vector<std::pair<std::string, bool>> other_options;
};

// The text table or JSON of identify --drive-gains. InputError for a missing --loaded, a bad payload option, logs
// of different joint counts, --method both, another identify option it does not use (--validate ...).
std::string run_drive_gains(const robot::RobotDescription& robot, const robot::RobotModel& model, const DriveGainOptions& o, const FitOptions& fit,
                            const std::string& method, const DriveGainInputs& inputs);

}  // namespace jacobid::options
