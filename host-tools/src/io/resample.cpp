// SPDX-License-Identifier: MIT
#include "io/resample.hpp"

#include <algorithm>
#include <cmath>

namespace jacobid::io {

double median_step(const std::vector<double>& t) {
    if (t.size() < 2) return 0.0;
    std::vector<double> steps(t.size() - 1);
    for (std::size_t i = 0; i + 1 < t.size(); ++i) steps[i] = t[i + 1] - t[i];
    const auto mid = steps.begin() + static_cast<std::ptrdiff_t>(steps.size() / 2);
    std::nth_element(steps.begin(), mid, steps.end());
    return *mid;
}

UniformGrid uniform_grid(const std::vector<double>& t, double max_step, double period) {
    UniformGrid g;
    if (t.size() < 2) return g;
    double sum = 0.0;
    std::size_t count = 0;
    for (std::size_t i = 0; i + 1 < t.size(); ++i) {
        const double step = t[i + 1] - t[i];
        if (step <= max_step) {
            sum += step;
            ++count;
        }
    }
    g.start = t.front();
    g.period = period > 0.0 ? period : count > 0 ? sum / static_cast<double>(count) : (t.back() - t.front()) / static_cast<double>(t.size() - 1);
    // The last grid point stays inside the log (no extrapolation); 1e-9 of a period absorbs rounding.
    const double points = std::floor((t.back() - t.front()) / g.period + 1e-9) + 1.0;
    g.samples = std::isfinite(points) && points > 0.0 && points < 1e15 ? static_cast<std::size_t>(points) : 0;  // 0: no usable grid
    return g;
}

std::vector<double> resample(const std::vector<double>& t, const std::vector<double>& x, const UniformGrid& grid, Interpolation method) {
    const std::size_t n = t.size();
    // Times relative to the first sample: Unix-second stamps (1.6e9 s) would lose the sub-millisecond
    // differences the spline needs.
    std::vector<double> u(n);
    for (std::size_t i = 0; i < n; ++i) u[i] = t[i] - t.front();
    // Natural cubic spline: second derivatives m from the tridiagonal system (Thomas algorithm), m = 0 at
    // both ends. The ends lose accuracy (O(h^2) over a few samples), which the differentiators crop anyway.
    std::vector<double> m(n, 0.0);
    if (method == Interpolation::CubicSpline && n > 2) {
        std::vector<double> diag(n), rhs(n), upper(n);
        for (std::size_t i = 1; i + 1 < n; ++i) {
            const double h0 = u[i] - u[i - 1], h1 = u[i + 1] - u[i];
            diag[i] = 2.0 * (h0 + h1);
            upper[i] = h1;
            rhs[i] = 6.0 * ((x[i + 1] - x[i]) / h1 - (x[i] - x[i - 1]) / h0);
            if (i > 1) {
                const double factor = h0 / diag[i - 1];
                diag[i] -= factor * upper[i - 1];
                rhs[i] -= factor * rhs[i - 1];
            }
        }
        for (std::size_t i = n - 2; i >= 1; --i) {
            m[i] = (rhs[i] - upper[i] * m[i + 1]) / diag[i];
            if (i == 1) break;
        }
    }
    std::vector<double> out(grid.samples);
    std::size_t i = 0;
    const double offset = grid.start - t.front();
    for (std::size_t k = 0; k < grid.samples; ++k) {
        const double s = std::min(offset + static_cast<double>(k) * grid.period, u.back());
        while (i + 2 < n && u[i + 1] < s) ++i;
        const double h = u[i + 1] - u[i];
        const double b = (s - u[i]) / h, a = 1.0 - b;
        out[k] = a * x[i] + b * x[i + 1] + ((a * a * a - a) * m[i] + (b * b * b - b) * m[i + 1]) * h * h / 6.0;
    }
    return out;
}

}  // namespace jacobid::io
