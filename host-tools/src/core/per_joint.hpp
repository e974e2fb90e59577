// SPDX-License-Identifier: MIT
#pragma once
// An option given as one value for every joint or one value per joint (limits, noise, the pose): expanded to
// one per joint; none given: `fallback` for each. InputError naming the option otherwise.
#include <fmt/core.h>

#include <string>
#include <vector>

#include "core/errors.hpp"

namespace jacobid {

inline std::vector<double> per_joint(const std::vector<double>& given, std::size_t joints, double fallback, const std::string& what) {
    if (given.empty()) return std::vector<double>(joints, fallback);
    if (given.size() == 1) return std::vector<double>(joints, given.front());
    if (given.size() != joints) {
        throw InputError(fmt::format("{}: {} values for a robot with {} joints (give one value or one per joint)", what, given.size(), joints));
    }
    return given;
}

}  // namespace jacobid
