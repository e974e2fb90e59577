// SPDX-License-Identifier: MIT
#pragma once
// The motion `excite --criterion i-optimal` designs for (docs/excite.md, "Designing for the motion the model
// will serve"): the information per sample M of a reference motion, and the default reference, random
// point-to-point moves within the design's own limits (the moves of `jacobid simulate` without --trajectory:
// quintic steps to targets drawn uniformly within the position range, within the velocity and acceleration
// limits).
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "excite/excitation_problem.hpp"
#include "excite/motion_information.hpp"
#include "robot/robot_model.hpp"

namespace jacobid::excite {

// M = (1 / N) sum over the N samples counted of W_i^T S^-1 W_i: trace(M C) is the mean over the motion of the
// predicted variance of the model's torque, each joint's in units of its noise variance.
Eigen::MatrixXd reference_information(const robot::RobotModel& model, const SampledMotion& motion, const Eigen::VectorXd& noise_std);

// `duration` s of random moves sampled at `rate`, from `pose` at rest, targets uniform within each joint's
// [lower, upper] position limits, each move within its velocity and acceleration limits (an infinite limit:
// none). Seeded: the same seed gives the same motion.
SampledMotion random_moves(const std::vector<JointLimits>& limits, const Eigen::VectorXd& pose, double duration, double rate, std::uint64_t seed);

}  // namespace jacobid::excite
