// SPDX-License-Identifier: MIT
#pragma once
// The identification issue's accuracy bars against the paper's Table II truth (the simulator's default):
// inertial parameters within 1 %, Coulomb levels within 5 %, relative error norm below 2 %. Shared by every
// test that identifies a simulated 2R robot, whatever path the data took (CSV, firmware stream, candump).
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

namespace jacobid::test {

// |X^ - truth| / |truth| for parameter `name` of an `identify --format json` result.
inline double relative_error(const nlohmann::json& result, const char* name, double truth) {
    return std::abs(result["parameters"][name]["value"].get<double>() - truth) / std::abs(truth);
}

inline void expect_table2_bars(const nlohmann::json& result) {
    EXPECT_LT(relative_error(result, "ZZ1R", 3.496), 0.01);
    EXPECT_LT(relative_error(result, "ZZ2", 0.059), 0.01);
    EXPECT_LT(relative_error(result, "MX2", 0.124), 0.01);
    EXPECT_LT(relative_error(result, "FC1", 0.431), 0.05);
    EXPECT_LT(relative_error(result, "FC2", 0.1268), 0.05);
    EXPECT_LT(result["relative_error_norm"].get<double>(), 0.02);
}

}  // namespace jacobid::test
