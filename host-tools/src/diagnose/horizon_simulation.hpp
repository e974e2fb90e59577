// SPDX-License-Identifier: MIT
#pragma once
// Short-horizon simulation of an identified model against the measured positions: segments of a few
// tenths of a second, each started from the measured state (position from the log, velocity from the Jacobi
// estimate) and driven by the measured torque (linear between samples, read `delay` later when a torque
// delay was identified), integrated with RK4 at the log's sample period through robot::ForwardDynamics, as
// the simulator integrates the truth. Over a short horizon a model error shows as a position drift before
// the open-loop integration of noise dominates; over long horizons an open-loop PD-controlled robot drifts
// whatever the model.
#include <Eigen/Core>
#include <vector>

#include "identify/pipeline.hpp"
#include "robot/robot_model.hpp"

namespace jacobid::diagnose {

struct HorizonSettings {
    double horizon = 0.3;   // s
    double spacing = 0.5;   // s between segment starts
};

struct HorizonResult {
    std::size_t segments = 0;
    std::vector<double> rms_error;  // per joint, rad, over every simulated sample
    std::vector<double> end_error;  // per joint, rad, RMS of the error at the end of the segments
};

// x: the model's parameters (NaN counts as 0).
HorizonResult simulate_horizons(const robot::RobotModel& model, const Eigen::VectorXd& x, const identify::LogColumns& log,
                                const identify::StateEstimates& states, double delay, const HorizonSettings& settings);

}  // namespace jacobid::diagnose
