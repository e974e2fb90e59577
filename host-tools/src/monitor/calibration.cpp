// SPDX-License-Identifier: MIT
#include "monitor/calibration.hpp"

#include <algorithm>
#include <cmath>

namespace jacobid::monitor {
namespace {

// The (1 - a) quantile (the k-th largest, k = floor(a * size) + 1); 0 for no values.
double upper_quantile(std::vector<double>& values, double a) {
    if (values.empty()) return 0.0;
    const auto k = std::min(values.size() - 1, static_cast<std::size_t>(std::floor(a * static_cast<double>(values.size()))));
    std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), values.end(), std::greater<double>());
    return values[k];
}

}  // namespace

std::vector<JointCalibration> calibrate(const std::vector<Replay>& replays, double a, double margin) {
    const std::size_t n = replays.empty() ? 0 : replays.front().external.size();
    std::vector<JointCalibration> out(n);
    for (std::size_t j = 0; j < n; ++j) {
        std::vector<double> moving, standing;
        JointCalibration& c = out[j];
        for (const Replay& r : replays) {
            for (std::size_t i = 0; i < r.t.size(); ++i) {
                const double v = std::abs(r.external[j][i]);
                if (r.standing[j][i]) {
                    standing.push_back(std::max(v - r.band[j][i], 0.0));
                    c.max_band = std::max(c.max_band, r.band[j][i]);
                } else {
                    moving.push_back(v);
                }
            }
        }
        c.moving_samples = moving.size();
        c.standing_samples = standing.size();
        c.thresholds.moving = (1.0 + margin) * upper_quantile(moving, a);
        c.thresholds.standing = (1.0 + margin) * upper_quantile(standing, a);
        // A state never seen: the other state's threshold, the band included (a standing joint's estimate
        // is inside band + standing; moving, the band is friction the model subtracts, so no looser).
        if (moving.empty() && !standing.empty()) {
            c.thresholds.moving = c.max_band + c.thresholds.standing;
            c.note = "never moved in the calibration logs: moving threshold = band + standing threshold";
        } else if (standing.empty() && !moving.empty()) {
            c.thresholds.standing = c.thresholds.moving;
            c.note = "never stood in the calibration logs: standing threshold = moving threshold";
        }
    }
    return out;
}

}  // namespace jacobid::monitor
