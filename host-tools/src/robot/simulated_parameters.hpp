// SPDX-License-Identifier: MIT
#pragma once
// The true parameters a simulation integrates, checked for physical possibility first. A robot no physics
// can move (a negative mass, a negative viscous friction that feeds energy in, a mass matrix that is not
// positive definite somewhere in the joint range, values or joint limits beyond what a double can carry
// through the dynamics) would otherwise diverge to nan rows or stop inside the dynamics; here it is an
// InputError naming the description and the parameter, joint or configuration at fault.
#include <Eigen/Core>

#include "robot/robot_description.hpp"
#include "robot/robot_model.hpp"

namespace jacobid::robot {

// true_parameters(description, model), after the checks above.
Eigen::VectorXd simulated_parameters(const RobotDescription& description, const RobotModel& model);

}  // namespace jacobid::robot
