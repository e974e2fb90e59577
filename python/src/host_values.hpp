// SPDX-License-Identifier: MIT
#pragma once
// The host functions' shared arguments (host_bindings.cpp): a robot, and a log of identify as the job reads it.
// fleet_bindings.cpp's plan / factor / merge take the same ones.
#include <pybind11/pybind11.h>

#include <memory>
#include <string>
#include <vector>

#include "job/identify_inputs.hpp"
#include "robot/robot_description.hpp"
#include "robot/robot_model.hpp"

namespace jacobid::python {

// A robot description and its model (robot/robot_description.hpp), as `--robot FILE` loads them.
struct Robot {
    robot::RobotDescription description;
    std::shared_ptr<const robot::RobotModel> model;
};

// load_robot(path=None): --robot's reading; None: the paper's planar 2R.
Robot load_robot(const pybind11::object& path, const pybind11::args& extra, const pybind11::kwargs& keywords);

// The `robot` argument of simulate, identify and diagnose: a Robot, or what load_robot reads (a path; None: the planar 2R).
Robot robot_of(const pybind11::handle& value);

// A log of identify (job/identify_inputs.hpp): a path, read by the job as --in reads it, or arrays (a tuple (t, q,
// tau), simulate()'s dict) made into a table here. `option` names it in messages.
job::LogSource log_source(const Robot& r, const pybind11::handle& source, const std::string& time_column, const std::string& option);

// identify's `log` as the job's sources: one log, or each of a list (named --in[k]).
std::vector<job::LogSource> log_sources(const Robot& r, const pybind11::handle& source, const std::string& time_column);

// What a Robot is pickled as: the absolute path of its description; None for the built-in planar 2R.
pybind11::object robot_path(const Robot& r);

// identify's `log`: one log, or a list of logs identified together (--in a --in b).
bool several_logs(const pybind11::handle& value);

}  // namespace jacobid::python
