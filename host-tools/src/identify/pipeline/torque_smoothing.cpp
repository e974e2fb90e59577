// SPDX-License-Identifier: MIT
#include "identify/pipeline/torque_smoothing.hpp"

namespace jacobid::identify {

std::vector<double> torque_smoothing_kernel(const std::vector<double>& velocity_weights, double ts) {
    const std::size_t taps = velocity_weights.size();
    std::vector<double> s(taps, 0.0);
    if (taps < 2) return s;
    // g_k = -Ts sum_{i<=k} c_i for k = 0 .. taps - 2 (g_{taps-1} = -Ts sum c = 0 for a derivative kernel).
    double cumulative = 0.0, previous = 0.0;
    for (std::size_t k = 0; k + 1 < taps; ++k) {
        cumulative += velocity_weights[k];
        const double g = -ts * cumulative;
        s[k] += 0.5 * (previous + g);  // s_k = (g_{k-1} + g_k) / 2
        previous = g;
    }
    s[taps - 1] = 0.5 * previous;
    return s;
}

}  // namespace jacobid::identify
