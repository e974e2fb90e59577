// SPDX-License-Identifier: MIT
#pragma once
// The joints' position and torque columns of a CSV log, as a robot description names them, with the
// log's uniform time axis checked (shared by `jacobid identify` and `jacobid diagnose`).
#include <string>

#include "identify/pipeline.hpp"
#include "io/csv_table.hpp"
#include "robot/robot_description.hpp"

namespace jacobid::identify {

// Pointers into `table` (which must outlive the result). InputError names the file and a missing column,
// or the time column's first non-uniform step.
LogColumns log_columns(const io::CsvTable& table, const robot::RobotDescription& robot, const std::string& time_column,
                       double time_tolerance);

}  // namespace jacobid::identify
