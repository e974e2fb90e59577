// SPDX-License-Identifier: MIT
#pragma once
// The frequencies identify must pass flat for a designed motion (docs/excite.md, "Identifying the design"):
// identify's automatic bandwidth is the frequency below which 99 % of the velocity's energy lies, and it puts
// its differentiators (and the torque's smoothing) at 10 x that. A design that swings the joints over most of
// their range at the top of its harmonics has a model torque whose spectrum reaches several times its
// velocity's (cos q of a 2.4 rad swing at 0.5 Hz has harmonics to ~2 Hz); the smoothing's passband then
// differs between the torque and the regressor columns computed from the positions, and the estimate is biased
// (measured: 2.8 x the validation error of random moves with identify's defaults, 0.72 x with --cutoff 20).
// So excite gives the cutoff that passes the torque: 10 x the frequency below which 99 % of the model torque's
// energy lies, each joint's torque divided by its noise std (what the estimate weighs).
#include <Eigen/Core>
#include <algorithm>
#include <vector>

namespace jacobid::excite {

inline constexpr double kEnergyFraction = 0.99;  // identify's bandwidth rule (identify/bandwidth.hpp)
inline constexpr double kCutoffRatio = 10.0;     // identify's differentiator cutoff / bandwidth

// The frequency (Hz) below which `fraction` of the summed energy of the signals (each times its weight, mean
// removed) lies; signals sampled at `rate` Hz, all of one length (>= 2).
double energy_frequency(const std::vector<std::vector<double>>& signals, const std::vector<double>& weights, double rate, double fraction = kEnergyFraction);

struct IdentificationBandwidth {
    double velocity_hz = 0.0;  // identify's automatic bandwidth on this motion (noise-free)
    double torque_hz = 0.0;    // the model torque's, each joint over its noise std
    double default_cutoff_hz() const { return kCutoffRatio * velocity_hz; }
    double recommended_cutoff_hz() const { return kCutoffRatio * std::max(velocity_hz, torque_hz); }
};
IdentificationBandwidth identification_bandwidth(const std::vector<std::vector<double>>& qd, const std::vector<std::vector<double>>& tau,
                                                 const Eigen::VectorXd& noise_std, double rate);

}  // namespace jacobid::excite
