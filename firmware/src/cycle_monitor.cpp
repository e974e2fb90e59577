// SPDX-License-Identifier: MIT
#include "jacobid/firmware/cycle_monitor.hpp"

#include <cmath>

namespace jacobid::firmware {

const char* to_string(MonitorAction action) noexcept { return action == MonitorAction::Stop ? "stop" : "flag"; }

void CycleMonitor::disable() noexcept {
    observer_.reset();
    terms_.reset();
    joints_ = 0;
    row_ = MonitorRow{};
}

std::string CycleMonitor::configure(const MonitorModel& m, std::size_t joints, double sample_period) {
    disable();
    if (m.chain.size() != joints) {
        return "monitor.robot: " + std::to_string(m.chain.size()) + " joints, but fw.yaml has " + std::to_string(joints);
    }
    if (m.friction.size() != joints || m.thresholds.size() != joints || m.coulomb.size() != joints) {
        return "monitor: the model's friction, thresholds and Coulomb functions must have one entry per joint";
    }
    robot::KinematicChain<N> chain;
    for (std::size_t j = 0; j < joints; ++j) {
        if (const robot::ChainError e = chain.add(m.chain[j]); e != robot::ChainError::Ok) {
            return "monitor.robot: joint " + std::to_string(j + 1) + ": " + robot::to_string(e);
        }
    }
    robot::RneaRegressor<N> regressor(chain, m.gravity, m.options);
    for (std::size_t j = 0; j < joints; ++j) regressor.set_coulomb(static_cast<int>(j), m.coulomb[j]);
    if (static_cast<std::size_t>(regressor.parameter_count()) != m.standard.size()) {
        return "monitor.robot: " + std::to_string(m.standard.size()) + " standard parameters, the chain's layout has " +
               std::to_string(regressor.parameter_count());
    }
    typename robot::RneaRegressor<N>::Parameters X = robot::RneaRegressor<N>::Parameters::Zero();
    for (std::size_t i = 0; i < m.standard.size(); ++i) X[static_cast<Eigen::Index>(i)] = m.standard[i];
    if (!(m.gain > 0.0) || !std::isfinite(m.gain)) return "monitor.thresholds: the observer gain must be > 0 (1/s)";
    terms_.emplace(regressor, X);
    robot::JointFriction<N> friction(regressor, X);
    for (std::size_t j = 0; j < joints; ++j) {
        friction.set_joint(static_cast<int>(j), m.friction[j]);
        detector_.set_joint(static_cast<int>(j), m.thresholds[j]);
    }
    detector_.set_confirm(m.confirm);
    detector_.reset();
    observer_.emplace(*terms_, friction, Joints::Constant(m.gain), sample_period);
    if (observer_->valid() != robot::EstimatorStatus::Ok) {
        disable();
        return "monitor: the observer gain and the sample period must be > 0";
    }
    joints_ = joints;
    row_ = MonitorRow{};
    return {};
}

const MonitorRow& CycleMonitor::step(const Joints& q, const Joints& qd, const Joints& tau, bool valid, bool trusted) noexcept {
    row_.over = 0;
    row_.contact = false;
    if (!observer_ || !valid) return row_;
    if (observer_->step(q, qd, tau, estimate_) != robot::EstimatorStatus::Ok) {
        // A non-finite input (a held NaN of a joint never heard from): no estimate, and nothing to detect on.
        detector_.confirmed(0);
        return row_;
    }
    row_.started = true;
    for (std::size_t j = 0; j < joints_; ++j) row_.external[j] = estimate_.external[static_cast<Eigen::Index>(j)];
    row_.over = trusted ? detector_.detect(estimate_, static_cast<int>(joints_)) : 0u;
    row_.contact = detector_.confirmed(row_.over);
    return row_;
}

}  // namespace jacobid::firmware
