// SPDX-License-Identifier: MIT
#pragma once
// The frequencies identify must pass flat for a designed motion (docs/excite.md, "Identifying the design"):
// identify puts its differentiators (and the torque's smoothing) at 10 x its automatic bandwidth. A design that
// swings the joints over most of their range at the top of its harmonics has a model torque whose spectrum
// reaches several times its velocity's (cos q of a 2.4 rad swing at 0.5 Hz has harmonics to ~2 Hz); if the
// smoothing's passband stopped at 10 x the velocity's band, it would differ between the torque and the
// regressor columns computed from the positions, and the estimate would be biased (measured: 2.44 x the
// validation error of random moves with a velocity-only bandwidth, 0.79 x with --cutoff 20). identify's
// differentiators therefore take the larger of the velocity's and the torque's band (identify/plan/bandwidth.hpp); excite runs
// that same code on the design (the noise-free positions, and the model torque with the noise the design is
// made for as each joint's floor), and names a cutoff only when identify's own would still miss the torque.
#include <Eigen/Core>
#include <algorithm>
#include <vector>

namespace jacobid::excite {

inline constexpr double kCutoffRatio = 10.0;  // identify's differentiator cutoff / bandwidth

struct IdentificationBandwidth {
    double velocity_hz = 0.0;   // 99 % of the velocity's energy (identify's energy frequency)
    double torque_hz = 0.0;     // the widest joint's 99 % of its model torque's energy (its noise std as the floor)
    double automatic_hz = 0.0;  // identify's automatic bandwidth on this motion (F_p at 5 x)
    double differentiator_hz = 0.0;  // identify's differentiators' bandwidth on it (the torque's band too)
    double default_cutoff_hz() const { return kCutoffRatio * differentiator_hz; }
    double recommended_cutoff_hz() const { return kCutoffRatio * std::max(velocity_hz, torque_hz); }
};
// q, tau per joint (all of one length), sampled at `rate` Hz; noise_std per joint (per sample).
IdentificationBandwidth identification_bandwidth(const std::vector<std::vector<double>>& q, const std::vector<std::vector<double>>& tau,
                                                 const Eigen::VectorXd& noise_std, double rate);

}  // namespace jacobid::excite
