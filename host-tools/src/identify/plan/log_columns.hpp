// SPDX-License-Identifier: MIT
#pragma once
// The joints' position and torque columns of a CSV log, as a robot description names them, with the
// log's uniform time axis checked and the positions within the joints' bounds (shared by `jacobid identify` and `jacobid diagnose`).
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "identify/pipeline/pipeline.hpp"
#include "io/csv_table.hpp"
#include "io/position_bounds.hpp"
#include "robot/robot_description.hpp"

namespace jacobid::identify {

// Where joint j's logged positions may be (io/position_bounds.hpp): nullopt when the description gives
// no limits for it (the defaults are not checked).
std::optional<io::PositionBounds> position_bounds(const robot::RobotDescription& robot, std::size_t j);

// The reference columns of joint j (0-based) that log_columns reads when the table has them, as jacobid
// simulate writes them: q_ref{j+1}, qd_ref{j+1} (what IDIM-IV and DIDIM simulate along).
std::array<std::string, 2> reference_column_names(std::size_t j);

// Pointers into `table` (which must outlive the result). InputError names the file and a missing column,
// or the time column's first non-uniform step. grid_period > 0 (a segment of a split log, on that grid): a
// table of fewer than 2 rows takes it as its period instead of failing, so that the segment is reported unused.
LogColumns log_columns(const io::CsvTable& table, const robot::RobotDescription& robot, const std::string& time_column,
                       double time_tolerance, double grid_period = 0.0);

// A log held in memory (e.g. simulated from code): joint j's positions q[j] (rad) and torques tau[j] (N.m),
// all of one length, sampled every `sample_period` seconds from `start_time`. Columns are named q1.., tau1..;
// pointers into q and tau, which must outlive the result. InputError for mismatched lengths or joint
// counts, or a sample period that is not positive.
// `log`'s torque columns in `table`, where log_columns found them, made writable: set as log.own_tau by an
// owner that reads them no more, so that the identification aligns them in place (LogColumns::own_tau).
std::vector<std::vector<double>*> writable_torques(io::CsvTable& table, const LogColumns& log);

LogColumns log_columns(const std::vector<std::vector<double>>& q, const std::vector<std::vector<double>>& tau, double sample_period,
                       const std::string& source, double start_time = 0.0);

}  // namespace jacobid::identify
