// SPDX-License-Identifier: MIT
#include "io/position_bounds.hpp"

#include <fmt/core.h>

namespace jacobid::io {

std::string PositionBounds::refusal(double q) const {
    return fmt::format("position {:.10g} is outside {}'s limits [{:g}, {:g}] by more than their range {:g} (an outlier? a position in "
                       "other units?); remove or repair the sample",
                       q, joint, lower, upper, margin());
}

}  // namespace jacobid::io
