// SPDX-License-Identifier: MIT
#include "sim/torque_delay_line.hpp"

#include <cmath>

namespace jacobid::sim {

const Eigen::VectorXd& TorqueDelayLine::push(const Eigen::VectorXd& tau) {
    const double lag = delay_ / period_;  // in samples
    const auto whole = static_cast<std::size_t>(std::floor(lag));
    const double frac = lag - static_cast<double>(whole);
    history_.push_back(tau);
    while (history_.size() > whole + 2) history_.pop_front();
    const std::size_t newest = history_.size() - 1;
    // Samples `whole` and `whole + 1` back from the newest, clamped to the oldest one kept.
    const Eigen::VectorXd& a = history_[newest >= whole ? newest - whole : 0];
    const Eigen::VectorXd& b = history_[newest >= whole + 1 ? newest - whole - 1 : 0];
    out_ = (1.0 - frac) * a + frac * b;
    return out_;
}

}  // namespace jacobid::sim
