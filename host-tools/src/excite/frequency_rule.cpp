// SPDX-License-Identifier: MIT
#include "excite/frequency_rule.hpp"

#include <algorithm>
#include <cmath>

namespace jacobid::excite {

double auto_base_frequency(double duration, const std::vector<JointLimits>& limits) {
    double periods = std::max(2.0, std::ceil(duration / kMaxPeriod - 1e-9));
    const double top = top_frequency(limits);
    while (periods > 2.0 && top * duration / periods < kMinHarmonics) periods -= 1.0;
    return periods / duration;
}

double top_frequency(const std::vector<JointLimits>& limits) {
    double top = 0.0;
    for (const JointLimits& l : limits) {
        if (std::isfinite(l.velocity) && std::isfinite(l.acceleration)) top = std::max(top, l.acceleration / (2.0 * M_PI * l.velocity));
    }
    return top > 0.0 ? std::clamp(top, kMinTop, kMaxTop) : kDefaultTop;
}

int auto_harmonics(double base_frequency, const std::vector<JointLimits>& limits) {
    const int harmonics = static_cast<int>(std::floor(top_frequency(limits) / base_frequency + 1e-9));
    return std::clamp(harmonics, 3, kMaxHarmonics);
}

}  // namespace jacobid::excite
