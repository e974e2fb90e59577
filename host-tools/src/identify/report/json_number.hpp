// SPDX-License-Identifier: MIT
#pragma once
// A double as JSON: NaN and infinities are not JSON numbers, so they are written as null. Shared by identify's
// and payload's JSON.
#include <cmath>
#include <nlohmann/json.hpp>

namespace jacobid::identify {

inline nlohmann::json finite_json(double d) { return std::isfinite(d) ? nlohmann::json(d) : nlohmann::json(nullptr); }

}  // namespace jacobid::identify
