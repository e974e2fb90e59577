// SPDX-License-Identifier: MIT
#pragma once
// Bandwidth of the motion in a log, used to choose the differentiator windows and the decimation filter
// when the user gives none: the frequency below which `fraction` (99 %) of the velocity's energy lies,
// summed over the joints. Velocity spectrum = Welch average (Hann, 50 % overlap) of the first difference
// of the position, which is the spectrum a position-loop bandwidth omega_dyn shapes. Encoder quantization
// adds a white floor to q, i.e. a floor rising as f^2 in the velocity; at realistic resolutions it holds
// far less than 1 % of the velocity energy, so it does not move the estimate.
#include <vector>

namespace jacobid::identify {

struct BandwidthEstimate {
    double frequency = 0.0;   // Hz
    double resolution = 0.0;  // Hz, bin width of the spectrum
    bool moving = false;      // false: no velocity energy at all (every joint constant)
};

BandwidthEstimate estimate_motion_bandwidth(const std::vector<const std::vector<double>*>& positions, double sample_period,
                                            double fraction = 0.99);

}  // namespace jacobid::identify
