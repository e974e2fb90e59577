// SPDX-License-Identifier: MIT
#pragma once
// Non-uniformly sampled signals onto a uniform grid, for the Jacobi differentiator and the decimation
// filter, which assume one sample period (docs/method.md, "Non-uniform sampling": the interpolation, the
// grid period and the measured error against exact weights for the actual sample times).
#include <cstddef>
#include <vector>

namespace jacobid::io {

enum class Interpolation { Linear, CubicSpline };

// The uniform grid t0 + k * period, k = 0..samples-1, inside [t.front(), t.back()].
struct UniformGrid {
    double start = 0.0;
    double period = 0.0;
    std::size_t samples = 0;
};

// Grid period: `period` when > 0, else the mean of the steps no longer than `max_step` (gaps excluded), so
// that the grid keeps about as many samples as the log; the grid starts at the first sample. samples = 0
// when the period does not give a finite grid (a zero or denormal period).
UniformGrid uniform_grid(const std::vector<double>& t, double max_step, double period = 0.0);

// Values of the interpolant of (t, x) at the grid points; t strictly increasing, at least 2 samples.
// CubicSpline: natural cubic spline through every sample (C2, error O(h^4) inside the log).
std::vector<double> resample(const std::vector<double>& t, const std::vector<double>& x, const UniformGrid& grid,
                             Interpolation method = Interpolation::CubicSpline);

// Median of the steps t[i+1] - t[i].
double median_step(const std::vector<double>& t);

}  // namespace jacobid::io
