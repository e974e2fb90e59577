// SPDX-License-Identifier: MIT
#pragma once
// The time column of a log: strictly increasing and uniformly sampled within a stated tolerance.
#include <cstddef>
#include <vector>

#include "io/csv_table.hpp"

namespace jacobid::io {

struct TimeAxis {
    double sample_period = 0.0;  // seconds: (t_last - t_first) / (samples - 1)
    double start = 0.0;          // seconds
    std::size_t samples = 0;
};

// Default tolerance on each step: |t[i+1] - t[i] - Ts| <= tolerance * Ts.
constexpr double kDefaultTimeTolerance = 0.01;

// Checks `time` (column `column_name` of `table`) and returns its sample period. InputError names the line
// of the first step that is not positive or deviates from the median step by more than the tolerance.
TimeAxis check_uniform_time(const CsvTable& table, const std::string& column_name, double tolerance = kDefaultTimeTolerance);

}  // namespace jacobid::io
