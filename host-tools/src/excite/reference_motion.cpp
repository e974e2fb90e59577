// SPDX-License-Identifier: MIT
#include "excite/reference_motion.hpp"

#include <algorithm>
#include <cmath>

#include "sim/quintic_trajectory.hpp"

namespace jacobid::excite {

Eigen::MatrixXd reference_information(const robot::RobotModel& model, const SampledMotion& motion, const Eigen::VectorXd& noise_std) {
    // motion_information weighs each sample it evaluates by its stride, so its sum stands for every counted sample.
    return motion_information(model, motion, noise_std) / static_cast<double>(std::max<std::size_t>(1, motion.counted()));
}

SampledMotion random_moves(const std::vector<JointLimits>& limits, const Eigen::VectorXd& pose, double duration, double rate, std::uint64_t seed) {
    const std::size_t n = limits.size();
    std::vector<double> lower, upper;
    sim::MoveSettings moves;
    for (const JointLimits& l : limits) {
        lower.push_back(l.lower), upper.push_back(l.upper);
        moves.velocity_limit.push_back(l.velocity);
        moves.acceleration_limit.push_back(l.acceleration);
    }
    sim::QuinticTrajectory trajectory(std::vector<double>(pose.data(), pose.data() + pose.size()), lower, upper, moves, seed);
    SampledMotion m;
    m.q.resize(n), m.qd.resize(n), m.qdd.resize(n);
    const auto count = static_cast<std::size_t>(std::llround(duration * rate)) + 1;
    sim::ReferenceSample s;
    for (std::size_t i = 0; i < count; ++i) {
        trajectory.evaluate(static_cast<double>(i) / rate, s);
        for (std::size_t j = 0; j < n; ++j) m.q[j].push_back(s.q[j]), m.qd[j].push_back(s.qd[j]), m.qdd[j].push_back(s.qdd[j]);
    }
    return m;
}

}  // namespace jacobid::excite
