// SPDX-License-Identifier: MIT
#pragma once
// The base parameter set of a robot description as a person reads it (one regrouping relation per line,
// with the true values when the description gives parameters) or as JSON, for
// `jacobid identify --robot r.yaml --print-base`.
#include <nlohmann/json.hpp>
#include <string>

#include "robot/robot_description.hpp"
#include "robot/robot_model.hpp"

namespace jacobid::robot {

std::string base_parameter_text(const RobotDescription& description, const RobotModel& model);
nlohmann::json base_parameter_json(const RobotDescription& description, const RobotModel& model);

}  // namespace jacobid::robot
