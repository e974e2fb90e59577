// SPDX-License-Identifier: MIT
#include "diagnose/statistics.hpp"

#include <algorithm>
#include <cmath>

namespace jacobid::diagnose {

std::vector<double> autocorrelation(const Eigen::VectorXd& x, int max_lag) {
    const Eigen::Index n = x.size();
    std::vector<double> rho;
    if (n < 2) return rho;
    const Eigen::VectorXd d = x.array() - x.mean();
    const double c0 = d.squaredNorm();
    if (!(c0 > 0.0)) return std::vector<double>(static_cast<std::size_t>(std::max(0, max_lag)), 0.0);
    for (int k = 1; k <= max_lag && k < n; ++k) rho.push_back(d.head(n - k).dot(d.tail(n - k)) / c0);
    return rho;
}

double effective_sample_size(const Eigen::VectorXd& r) {
    const auto n = static_cast<double>(r.size());
    if (r.size() < 8) return std::max(1.0, n);
    const int max_lag = static_cast<int>(std::min<Eigen::Index>(r.size() / 4, 200));
    double sum = 0.0;
    for (double rho : autocorrelation(r, max_lag)) {
        if (rho <= 0.0) break;
        sum += rho;
    }
    return std::clamp(n / (1.0 + 2.0 * sum), 1.0, n);
}

double chi_square_survival(double x, int dof) {
    if (!(x > 0.0)) return 1.0;
    const double y = 0.5 * x;
    double q, a, term;  // Q(a, y) and y^a e^-y / Gamma(a + 1) at the current a
    if (dof % 2 == 1) {
        a = 0.5;
        q = std::erfc(std::sqrt(y));
        term = std::exp(0.5 * std::log(y) - y - std::lgamma(1.5));
    } else {
        a = 1.0;
        q = std::exp(-y);
        term = std::exp(std::log(y) - y - std::lgamma(2.0));
    }
    while (2.0 * a < dof) {
        q += term;
        a += 1.0;
        term *= y / a;
    }
    return std::clamp(q, 0.0, 1.0);
}

}  // namespace jacobid::diagnose
