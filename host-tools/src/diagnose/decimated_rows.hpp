// SPDX-License-Identifier: MIT
#pragma once
// The identification's decimated, filtered rows (Y_j and W_j per joint, exactly as `jacobid identify` folds
// them into its least squares: run_pipeline hands them out through identify::RowSink), plus what the
// diagnosis needs beside them, from the same run: each row's sample index and estimated state (for binning
// residuals by velocity, position, acceleration) and the full-rate filtered torque F_p(tau), from which Y is
// re-sampled when the torque channel is shifted in time.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "identify/pipeline/pipeline.hpp"
#include "identify/friction/torque_delay.hpp"
#include "robot/robot_model.hpp"

namespace jacobid::diagnose {

struct DecimatedRows {
    identify::PipelineInfo info;
    std::vector<std::string> names;   // regressor columns
    std::vector<double> t;            // s
    std::vector<std::size_t> sample;  // full-rate sample index of each row
    std::vector<Eigen::MatrixXd> w;   // per joint: rows x columns
    std::vector<Eigen::VectorXd> y;   // per joint: measured torque through F_p
    std::vector<Eigen::MatrixXd> state;  // per joint: rows x 3 (q, qd, qdd estimates, unfiltered)
    std::vector<std::vector<double>> tau_filtered;  // per joint, full rate
    double sample_period = 0.0;

    std::size_t rows() const { return t.size(); }
    int joints() const { return static_cast<int>(y.size()); }
    // Y of `joint` for the torque channel read `delay` seconds later (undoes a lag of `delay`).
    Eigen::VectorXd shifted_y(int joint, double delay) const;
    // Y of every joint for that delay (y itself for 0).
    std::vector<Eigen::VectorXd> shifted_ys(double delay) const;
};

DecimatedRows decimated_rows(const robot::RobotModel& model, const identify::LogColumns& log, const identify::PipelineSettings& settings);

// Several logs' rows one after another (diagnose --in a.csv --in b.csv), each log through `settings` (one plan
// imposed on all: identify::plan_segments' fixed settings; `plan` is that plan's info). The sample indices
// and the filtered torque are offset so that each row still reads its own log's torque when shifted in
// time, and each log's times follow the previous log's last sample (one campaign clock), so that binning
// the residual by time keeps the logs apart and in order.
DecimatedRows stacked_decimated_rows(const robot::RobotModel& model, const std::vector<identify::LogColumns>& logs,
                                     const identify::PipelineSettings& settings, const identify::PipelineInfo& plan);

// Torque columns read later: identify::shift_torques (identify/friction/torque_delay.hpp).
using identify::ShiftedTorques;
using identify::shift_torques;

}  // namespace jacobid::diagnose
