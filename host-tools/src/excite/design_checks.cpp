// SPDX-License-Identifier: MIT
#include "excite/design_checks.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>

#include "core/errors.hpp"

namespace jacobid::excite {

void require_room_to_move(const std::vector<JointLimits>& limits, const Eigen::VectorXd& pose, double base_frequency, const std::string& position_source) {
    const double w = 2.0 * M_PI * base_frequency;
    const std::string rule = fmt::format("less than the {:g} rad (or m) an excitation needs to be measured", kMinExcitationAmplitude);
    for (std::size_t j = 0; j < limits.size(); ++j) {
        const JointLimits& l = limits[j];
        const double by_velocity = l.velocity / w, by_acceleration = l.acceleration / (w * w);
        if (by_velocity < kMinExcitationAmplitude) {
            throw InputError(fmt::format("--velocity-limit: joint {}'s {:g} rad/s allows a motion of at most v / (2 pi f0) = {:.3g} rad at the base "
                                         "frequency f0 = {:g} Hz, {}; raise the limit or lower --base-frequency",
                                         j + 1, l.velocity, by_velocity, base_frequency, rule));
        }
        if (by_acceleration < kMinExcitationAmplitude) {
            throw InputError(fmt::format("--acceleration-limit: joint {}'s {:g} rad/s^2 allows a motion of at most a / (2 pi f0)^2 = {:.3g} rad at the "
                                         "base frequency f0 = {:g} Hz, {}; raise the limit or lower --base-frequency",
                                         j + 1, l.acceleration, by_acceleration, base_frequency, rule));
        }
        const auto k = static_cast<Eigen::Index>(j);
        const double room = std::min(pose[k] - l.lower, l.upper - pose[k]);
        if (room < kMinExcitationAmplitude) {
            throw InputError(fmt::format("--pose: joint {} at {:g} is {:.3g} from its limit in [{:g}, {:g}] ({}), {}; move the pose or widen the limits",
                                         j + 1, pose[k], room, l.lower, l.upper, position_source, rule));
        }
    }
}

void require_separable_design(const Design& design) {
    if (design.cond < kMaxDesignCond) return;
    throw InputError(fmt::format("the best design found has cond {:.3g} (column-scaled regressor), {:g} or more: its motion cannot separate the base "
                                 "parameters; it runs into joint {}'s {} limit (use {:.3f}): raise the limits (or the --time-limit / --starts)",
                                 design.cond, kMaxDesignCond, design.check.worst_joint + 1, to_string(design.check.worst_kind), design.check.worst));
}

}  // namespace jacobid::excite
