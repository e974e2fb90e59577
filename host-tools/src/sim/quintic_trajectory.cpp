// SPDX-License-Identifier: MIT
#include "sim/quintic_trajectory.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/errors.hpp"
#include "core/per_joint.hpp"

namespace jacobid::sim {
namespace {

// One limit per joint (infinity: none), each > 0.
std::vector<double> joint_limits(const std::vector<double>& given, std::size_t joints, const char* option) {
    for (const double v : given) {
        if (!(v > 0.0)) throw InputError(fmt::format("{}: {}: expected a limit > 0", option, v));
    }
    return per_joint(given, joints, std::numeric_limits<double>::infinity(), option);
}

}  // namespace

QuinticTrajectory::QuinticTrajectory(std::vector<double> start, std::vector<double> lower, std::vector<double> upper,
                                     MoveSettings settings, std::uint64_t seed)
    : lower_(std::move(lower)), upper_(std::move(upper)), settings_(settings), rng_(seed), from_(start), to_(std::move(start)) {
    velocity_limit_ = joint_limits(settings_.velocity_limit, to_.size(), "--velocity-limit");
    acceleration_limit_ = joint_limits(settings_.acceleration_limit, to_.size(), "--acceleration-limit");
    move_start_ = 0.0;
    move_end_ = 0.0;
    move_duration_ = 1.0;
    next_move();
}

void QuinticTrajectory::next_move() {
    from_ = to_;
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (std::size_t j = 0; j < to_.size(); ++j) to_[j] = lower_[j] + (upper_[j] - lower_[j]) * unit(rng_);
    move_start_ = move_end_;
    move_duration_ = settings_.min_duration + (settings_.max_duration - settings_.min_duration) * unit(rng_);
    for (std::size_t j = 0; j < to_.size(); ++j) {
        const double step = std::abs(to_[j] - from_[j]);
        move_duration_ = std::max({move_duration_, kQuinticPeakVelocity * step / velocity_limit_[j], std::sqrt(kQuinticPeakAcceleration * step / acceleration_limit_[j])});
    }
    move_end_ = move_start_ + move_duration_ + settings_.max_dwell * unit(rng_);
}

void QuinticTrajectory::evaluate(double t, ReferenceSample& out) {
    while (t >= move_end_) next_move();
    const std::size_t n = to_.size();
    out.q.resize(n);
    out.qd.resize(n);
    out.qdd.resize(n);
    const double T = move_duration_;
    const double s = std::clamp((t - move_start_) / T, 0.0, 1.0);
    // r(s) = 10 s^3 - 15 s^4 + 6 s^5: r(0) = 0, r(1) = 1, r' and r'' vanish at both ends.
    const double s2 = s * s, s3 = s2 * s;
    const double r = s3 * (10.0 - 15.0 * s + 6.0 * s2);
    const double dr = 30.0 * s2 * (1.0 - 2.0 * s + s2) / T;
    const double ddr = 60.0 * s * (1.0 - 3.0 * s + 2.0 * s2) / (T * T);
    for (std::size_t j = 0; j < n; ++j) {
        const double d = to_[j] - from_[j];
        out.q[j] = from_[j] + d * r;
        out.qd[j] = d * dr;
        out.qdd[j] = d * ddr;
    }
}

}  // namespace jacobid::sim
