// SPDX-License-Identifier: MIT
#pragma once
// The identified model as the contact monitor runs it (docs/monitor.md): a robot description (the YAML
// `identify --export-robot` writes, or any serial description with parameters) turned into the lib's
// fixed-size estimator pieces (rigid_body_terms.hpp, joint_friction.hpp), the same code a controller runs.
#include <memory>
#include <string>
#include <vector>

#include "jacobid/robot/external_torque.hpp"
#include "robot/robot_description.hpp"
#include "robot/serial_robot_model.hpp"

namespace jacobid::monitor {

constexpr int kJoints = robot::kMaxSerialJoints;  // capacity; a robot uses its first joints()
using Joints = robot::JointVector<kJoints>;

struct MonitorModel {
    robot::RobotDescription description;
    robot::SerialRobotConfig config;  // the chain the terms were built from (the controller builds its own from it)
    Eigen::VectorXd standard;         // standard parameters in the lib layout's order, friction included
    std::unique_ptr<robot::RigidBodyTerms<kJoints>> terms;
    robot::JointFriction<kJoints> friction;
    std::vector<std::string> notes;  // what the monitor leaves out of the description (printed once)
    int joints() const { return terms ? terms->joint_count() : 0; }
};

// InputError naming the file for a description that is not a serial robot (mdh, urdf) or is too large.
// `standing_velocity`: rad/s per joint below which a joint stands (one value for all, or one per joint),
// for at least `standing_time` s of samples `sample_period` apart; its band is (1 + band_margin) x its Coulomb level
// (one band margin for all, or one per joint).
MonitorModel load_monitor_model(const std::string& path, const std::vector<double>& standing_velocity, double standing_time, double sample_period,
                                const std::vector<double>& band_margin = {0.0});

}  // namespace jacobid::monitor
