// SPDX-License-Identifier: MIT
#include "excite/periodic_lowpass.hpp"

#include <cmath>
#include <stdexcept>

namespace jacobid::excite {

Eigen::MatrixXd periodic_lowpass(int samples, double period, double cutoff_hz, int order) {
    if (samples < 2 || !(period > 0.0) || !(cutoff_hz > 0.0) || order < 1) {
        throw std::invalid_argument("periodic_lowpass: needs samples >= 2, period > 0, cutoff > 0 and order >= 1");
    }
    const int n = samples;
    // The gain of each frequency k / T, k = 0 .. N / 2, counted with its -k twin (Nyquist, even N, once).
    Eigen::VectorXd weight(n / 2 + 1);
    for (int k = 0; 2 * k <= n; ++k) {
        const double g = 1.0 / (1.0 + std::pow(k / (period * cutoff_hz), 2.0 * order));
        weight[k] = k == 0 || 2 * k == n ? g : 2.0 * g;
    }
    // The circulant's first column: c_d = (1 / N) sum_k g(k / T) cos(2 pi k d / N).
    Eigen::VectorXd first(n);
    for (int d = 0; d < n; ++d) {
        double sum = 0.0;
        for (int k = 0; 2 * k <= n; ++k) sum += weight[k] * std::cos(2.0 * M_PI * static_cast<double>(k) * d / n);
        first[d] = sum / n;
    }
    Eigen::MatrixXd F(n, n);
    for (int a = 0; a < n; ++a) {
        for (int b = 0; b < n; ++b) F(a, b) = first[((a - b) % n + n) % n];
    }
    return F;
}

}  // namespace jacobid::excite
