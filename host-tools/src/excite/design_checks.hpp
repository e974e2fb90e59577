// SPDX-License-Identifier: MIT
#pragma once
// When an excitation design means nothing (issue 36: --velocity-limit 1e-9 "designed" a 1e-10 rad motion with
// cond 1.8e16, exit 0). Two rules, both InputError naming the option:
//   - before the design, each joint must have room to move at the base frequency: the amplitude its limits
//     allow a motion of period 1/f0 around the pose, v / (2 pi f0) for a velocity limit v, a / (2 pi f0)^2 for
//     an acceleration limit a, the distance from the pose to its nearer position limit, at least
//     kMinExcitationAmplitude (1 mrad or 1 mm: below it the encoder and the torque noise see nothing);
//   - after it, the base parameters must be separable: cond(W_s) (W column-scaled, information_criterion.hpp)
//     below kMaxDesignCond = 1e8, beyond which W_s' W_s is singular in double precision.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "core/measurable_motion.hpp"
#include "excite/excitation_design.hpp"
#include "excite/excitation_problem.hpp"

namespace jacobid::excite {

inline constexpr double kMinExcitationAmplitude = kMinMeasurableMotion;
inline constexpr double kMaxDesignCond = 1e8;

// `position_source`: where the position limits came from ("the robot description", "--position-limit").
void require_room_to_move(const std::vector<JointLimits>& limits, const Eigen::VectorXd& pose, double base_frequency, const std::string& position_source);

// The design's cond against kMaxDesignCond, naming the limit it runs into.
void require_separable_design(const Design& design);

}  // namespace jacobid::excite
