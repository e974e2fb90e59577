// SPDX-License-Identifier: MIT
#pragma once
// `jacobid payload --arm FILE`: the arm the payload is measured against, held at its identified values.
//   - `jacobid identify --format json` output: every base parameter's `value` and `std` (identify's std,
//     diagonal: identify writes no correlations, so the arm's share of the payload's std is that of
//     independent parameters), each joint's Coulomb smoothing from `coulomb_smoothing.joints[].alpha` and the
//     torque delay it applied; the robot is --robot's description;
//   - a robot description (`identify --export-robot`, or any YAML of the same robot): its parameters, no std.
#include <Eigen/Core>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "robot/robot_description.hpp"
#include "robot/robot_model.hpp"
#include "robot/serial_robot_model.hpp"

namespace jacobid::payload {

struct ArmModel {
    std::string source;
    robot::RobotDescription description;          // its Coulomb smoothing fixed
    std::unique_ptr<robot::RobotModel> model;      // a SerialRobotModel
    const robot::SerialRobotModel* serial = nullptr;
    Eigen::VectorXd values;                        // base parameters, model order
    Eigen::VectorXd std_dev;                       // per base parameter; empty: none in the file
    std::vector<std::string> fallbacks;            // not identified in the JSON: the description's value kept (std 0)
    std::optional<double> torque_delay;            // s, applied by that identification (JSON only)
    bool base_only = false;                        // JSON: base parameters only (the description's standard values stay)
};

// InputError naming the file and key for an unreadable file, a parameter the model has and the file lacks, a
// description of another joint count, or a model without per-link standard parameters (planar2r).
ArmModel load_arm(const std::string& path, const robot::RobotDescription& robot);

}  // namespace jacobid::payload
