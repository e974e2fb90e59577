// SPDX-License-Identifier: MIT
#pragma once
// The unknown initial state of presliding friction on a log the identification did not see (docs/method.md,
// "Presliding friction (Dahl)"). A joint that stands still when the log starts holds the friction of its last
// motion before the recording, F_d s0 with an s0 nothing in the log's past can tell; a joint that then
// stands for the whole log keeps it. It is observed, as a controller would at start-up, from the torque
// held during the first `window` seconds: s0_j = (mean tau_j - mean model torque at rest with s = 0) / FDj,
// clamped to [-1, 1]. Only the initial state is estimated (the parameters, FDj and x_p included, stay the
// identification's); a joint that moves more than the play band in the window starts at 0 (its state is
// rewritten within x_p of motion anyway).
#include <Eigen/Core>
#include <memory>
#include <vector>

#include "identify/pipeline/pipeline.hpp"
#include "robot/presliding_model.hpp"

namespace jacobid::identify {

std::vector<double> observe_initial_presliding_state(const robot::PreslidingModel& model, const LogColumns& log, const Eigen::VectorXd& x,
                                                     double window = 1.0);

// `model` itself, or (a PreslidingModel) a copy starting from the observed initial state, kept in `holder`.
const robot::RobotModel& with_observed_initial_state(const robot::RobotModel& model, const LogColumns& log, const Eigen::VectorXd& x,
                                                     std::unique_ptr<robot::RobotModel>& holder);

}  // namespace jacobid::identify
