// SPDX-License-Identifier: MIT
#include "excite/identification_bandwidth.hpp"

#include "identify/plan/bandwidth.hpp"

namespace jacobid::excite {

IdentificationBandwidth identification_bandwidth(const std::vector<std::vector<double>>& q, const std::vector<std::vector<double>>& tau,
                                                 const Eigen::VectorXd& noise_std, double rate) {
    std::vector<const std::vector<double>*> positions, torques;
    for (const auto& x : q) positions.push_back(&x);
    for (const auto& x : tau) torques.push_back(&x);
    const std::vector<double> noise(noise_std.data(), noise_std.data() + noise_std.size());
    const double ts = 1.0 / rate;
    identify::BandwidthEstimate motion = identify::estimate_motion_bandwidth(positions, ts, {}, kCutoffRatio);
    identify::TorqueBandwidth torque = identify::estimate_torque_bandwidth(torques, ts, {}, identify::torque_highest(motion, kCutoffRatio),
                                                                           identify::kMotionEnergyFraction, 1, noise);
    const identify::BandwidthEstimate b = identify::with_torque(std::move(motion), std::move(torque), kCutoffRatio);
    IdentificationBandwidth r;
    r.velocity_hz = b.energy_frequency;
    r.torque_hz = b.torque.frequency;
    r.automatic_hz = b.frequency;
    r.differentiator_hz = b.differentiator_frequency;
    return r;
}

}  // namespace jacobid::excite
