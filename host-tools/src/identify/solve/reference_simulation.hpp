// SPDX-License-Identifier: MIT
#pragma once
// The identified model simulated in closed loop along a log's reference (docs/method.md, "Estimators"):
// the states IDIM-IV builds its instruments from and DIDIM its regressor from. The loop is the
// simulator's own (sim/closed_loop.hpp) with the robot description's controller, driven by the logged
// q_ref and qd_ref (linear between samples at the control instants), from the reference's first sample.
#include <Eigen/Core>
#include <string>

#include "identify/pipeline/pipeline.hpp"
#include "robot/robot_description.hpp"
#include "robot/robot_model.hpp"

namespace jacobid::identify {

// InputError (one line naming the log, or the description, and what is missing) unless `log` has a
// reference for every joint and `description` a controller; `estimator` names the option in the message.
void require_reference_simulation(const LogColumns& log, const robot::RobotDescription& description, const std::string& estimator);

// The closed-loop states of `model` with parameters `x` along the log's reference, one value per log
// sample, in a StateEstimates over [info.first, info.last) whose torques are the log's own, unfiltered
// (the simulated regressor is exact: only F_p filters it, so only F_p may filter the torque). `nominal`
// and the description's true parameters give the gains of a controller given by its bandwidth (omega).
// InputError if x gives no positive definite inertia matrix on the way.
StateEstimates simulate_along_reference(const robot::RobotModel& model, const Eigen::VectorXd& x, const robot::RobotDescription& description,
                                        const robot::RobotModel& nominal, const LogColumns& log, const PipelineInfo& info);

// What the iterated estimators simulate with and fold the simulated states through: one log (the torques
// already aligned), its pipeline plan, the model fitted and the description's controller.
struct ReferenceSimulation {
    const robot::RobotDescription& description;
    const robot::RobotModel& nominal;
    const robot::RobotModel& model;
    const LogColumns& log;
    const PipelineSettings& pipeline;
    PipelineInfo info;  // plan_pipeline and estimate_states on log

    StateEstimates states(const Eigen::VectorXd& x) const { return simulate_along_reference(model, x, description, nominal, log, info); }
};

}  // namespace jacobid::identify
