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

// The sample periods a log may have: 10 us .. 100 ms per sample (100 kHz .. 10 Hz). Every robot controller
// logs inside it (drive current loops 10-40 kHz, joint controllers 125 Hz-8 kHz; the shared UR10e logs
// 10 ms, the pendubot 5 ms), and below 10 Hz the accelerations the identification differentiates are not
// resolved. Outside it a log is almost always in another unit than it is read in: a 1 kHz log in ms read
// as s steps 1 s, a 10 kHz one 0.1 s; ns stamps read as s step 1e6 s; a time.scale of 1e-9 on seconds
// steps 1e-12 s (issue 36: identify ran on them, off by 1e6 or 1e-12). The time column is also exempt from
// the +-1e30 bound on log values (nanosecond epochs are ~1e18), so this bound is what limits its steps.
constexpr double kMinSamplePeriod = 1e-5;
constexpr double kMaxSamplePeriod = 0.1;
// InputError "<where>: the median time step is 1 s, outside the plausible sample periods 10 us .. 100 ms per
// sample (...): is the time column in ms (1 ms per sample)? ..." outside [kMinSamplePeriod, kMaxSamplePeriod].
// `scale`: the seconds per unit the column was read with; `format`: the log format that set it (empty: a
// plain CSV, read in seconds).
void require_plausible_sample_period(double median_step, const std::string& where, double scale = 1.0, const std::string& format = "");

// Checks `time` (column `column_name` of `table`) and returns its sample period. InputError names the line
// of the first step that is not positive or deviates from the median step by more than the tolerance.
TimeAxis check_uniform_time(const CsvTable& table, const std::string& column_name, double tolerance = kDefaultTimeTolerance);

}  // namespace jacobid::io
