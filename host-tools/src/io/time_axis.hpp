// SPDX-License-Identifier: MIT
#pragma once
// The time column of a log: strictly increasing and uniformly sampled within a stated tolerance.
#include <cstddef>
#include <string>
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

// The longest sample period a log may have: the estimate stream's (1000 s). The time column is exempt from
// the +-1e30 bound on log values (nanosecond epochs are ~1e18), so its steps are bounded here: a log whose
// steps were 1e200 s ran into "too short for the window". (Periods below 1 ns are refused where a kernel or
// a grid is made from them.)
constexpr double kMaxSamplePeriod = 1e3;
// InputError "<where>: the median time step is ... s, expected a sample period of at most 1000 s ..." beyond it.
void require_plausible_sample_period(double median_step, const std::string& where);

// Checks `time` (column `column_name` of `table`) and returns its sample period. InputError names the line
// of the first step that is not positive or deviates from the median step by more than the tolerance.
TimeAxis check_uniform_time(const CsvTable& table, const std::string& column_name, double tolerance = kDefaultTimeTolerance);

}  // namespace jacobid::io
