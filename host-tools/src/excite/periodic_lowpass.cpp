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
    // The circulant's first column: c_d = (1 / N) sum_k g(k / T) cos(2 pi k d / N), the k and -k terms together.
    Eigen::VectorXd first(n);
    for (int d = 0; d < n; ++d) {
        double sum = 1.0;  // k = 0: g = 1
        for (int k = 1; 2 * k <= n; ++k) {
            const double g = 1.0 / (1.0 + std::pow(k / (period * cutoff_hz), 2.0 * order));
            const double term = g * std::cos(2.0 * M_PI * static_cast<double>(k) * d / n);
            sum += 2 * k == n ? term : 2.0 * term;  // Nyquist (even N) once, the others with their -k twin
        }
        first[d] = sum / n;
    }
    Eigen::MatrixXd F(n, n);
    for (int a = 0; a < n; ++a) {
        for (int b = 0; b < n; ++b) F(a, b) = first[((a - b) % n + n) % n];
    }
    return F;
}

}  // namespace jacobid::excite
