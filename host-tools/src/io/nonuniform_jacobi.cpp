// SPDX-License-Identifier: MIT
#include "io/nonuniform_jacobi.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

namespace jacobid::io {

std::vector<double> jacobi_at_sample_times(const KernelParams& p, const std::vector<double>& t, const std::vector<double>& x,
                                           const std::vector<double>& at) {
    const double h = 0.5 * p.window;
    const int n = p.order;
    const int degree = p.q + n;
    std::vector<double> out(at.size(), std::numeric_limits<double>::quiet_NaN());
    std::size_t lo = 0;
    for (std::size_t k = 0; k < at.size(); ++k) {
        const double c = at[k] - h * p.xi;  // window centre: the estimate refers to c + h xi
        if (c - h < t.front() || c + h > t.back()) continue;
        while (lo < t.size() && t[lo] < c - h) ++lo;
        std::size_t hi = lo;
        while (hi < t.size() && t[hi] <= c + h) ++hi;
        const auto m = static_cast<Eigen::Index>(hi - lo);
        if (m < degree + 1) continue;
        // Monomials in tau on [-1, 1] are well conditioned for the small degrees used (q + n <= ~8).
        Eigen::MatrixXd a(m, degree + 1);
        Eigen::VectorXd b(m);
        Eigen::Index rows = 0;
        for (std::size_t i = lo; i < hi; ++i) {
            const double tau = (t[i] - c) / h;
            // The sample's cell: halfway to its neighbours (the window ends bound the outer cells).
            const double left = i > 0 ? std::max(-1.0, 0.5 * (t[i - 1] + t[i] - 2.0 * c) / h) : -1.0;
            const double right = i + 1 < t.size() ? std::min(1.0, 0.5 * (t[i] + t[i + 1] - 2.0 * c) / h) : 1.0;
            const double w = std::pow(std::max(0.0, 1.0 - tau), p.mu) * std::pow(std::max(0.0, 1.0 + tau), p.kappa) * (right - left);
            if (!(w > 0.0)) continue;
            const double sw = std::sqrt(w);
            double power = 1.0;
            for (int d = 0; d <= degree; ++d) {
                a(rows, d) = sw * power;
                power *= tau;
            }
            b(rows) = sw * x[i];
            ++rows;
        }
        if (rows < degree + 1) continue;
        const Eigen::VectorXd coef = a.topRows(rows).colPivHouseholderQr().solve(b.head(rows));
        // n-th derivative of sum coef_d tau^d at xi, scaled from tau to seconds by h^-n.
        double value = 0.0;
        for (int d = n; d <= degree; ++d) {
            double falling = 1.0;
            for (int j = 0; j < n; ++j) falling *= d - j;
            value += coef(d) * falling * std::pow(p.xi, d - n);
        }
        out[k] = value / std::pow(h, n);
    }
    return out;
}

}  // namespace jacobid::io
