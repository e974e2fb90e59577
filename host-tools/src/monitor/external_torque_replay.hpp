// SPDX-License-Identifier: MIT
#pragma once
// A log replayed through the monitor's estimator, sample by sample as the controller would run it
// (docs/monitor.md): the Jacobi differentiator bank (differentiator_bank.hpp) for the states the log lacks,
// then the lib's momentum observer or direct residual (external_torque.hpp). Each output row is stamped with
// the time of the input sample that produced it, i.e. when a controller would know it (the bank's delay
// included), so that detection delays are the real ones.
#include <string>
#include <vector>

#include "io/csv_table.hpp"
#include "monitor/monitor_model.hpp"

namespace jacobid::monitor {

enum class Estimator { Observer, Residual };
const char* to_string(Estimator e);

struct EstimatorSettings {
    Estimator estimator = Estimator::Observer;
    double gain = 100.0;                // 1/s: the observer's K (every joint)
    double velocity_window = 0.02;      // s: the bank's position and velocity windows
    double acceleration_window = 0.04;  // s: the residual's acceleration window
    // Evaluation point of the kernels: 0 central (delay: half the window), towards 1 causal (delay h (1 - xi),
    // more noise); h (1 - xi) must be a whole number of samples (differentiator_bank.hpp).
    double xi = 0.0;
    // Measured velocities (qd1.. columns, e.g. the UR10e's) instead of the bank's, for the observer: no
    // differentiator delay at all.
    bool measured_velocity = true;
};

// One log: uniform time, the robot's positions and torques, measured velocities when it has them.
struct MonitorLog {
    std::string source;
    double sample_period = 0.0;
    std::vector<double> t;
    std::vector<std::vector<double>> q, qd, tau;  // per joint; qd empty when not logged
};

// The log's columns (time_column, then the description's position and torque columns, qd1.. when present)
// from a table already read; InputError naming the file for a non-uniform time column.
MonitorLog monitor_log(const io::CsvTable& table, const robot::RobotDescription& robot, const std::string& time_column, double time_tolerance);

struct Replay {
    double delay = 0.0;  // s: the differentiator bank's delay (0 with measured velocities)
    std::vector<double> t;  // s: when each estimate is known
    std::vector<std::vector<double>> external, band;  // per joint, N.m
    std::vector<std::vector<char>> standing;          // per joint
    std::vector<std::size_t> row;                     // the log row each estimate is known at
};

// InputError for settings the bank rejects (naming the option) or a log too short for the windows.
Replay replay(const MonitorModel& model, const EstimatorSettings& settings, const MonitorLog& log);

}  // namespace jacobid::monitor
