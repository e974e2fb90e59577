// SPDX-License-Identifier: MIT
#pragma once
// The torque channel of a log lagging the position channel by a fixed delay (drive current sampled earlier
// than the encoder, or stamped later on the bus). Linear interpolation between logged samples of the true
// torque: exact when the log rate is a multiple of the control rate, because the drive's first-order hold
// makes the torque piecewise linear between control instants. Before the first sample the torque is held.
#include <Eigen/Core>
#include <deque>

namespace jacobid::sim {

class TorqueDelayLine {
public:
    TorqueDelayLine(double delay, double sample_period) : delay_(delay), period_(sample_period) {}
    // Appends the true torque of the next sample and returns the torque `delay` earlier.
    const Eigen::VectorXd& push(const Eigen::VectorXd& tau);

private:
    double delay_, period_;
    std::deque<Eigen::VectorXd> history_;  // newest last
    Eigen::VectorXd out_;
};

}  // namespace jacobid::sim
