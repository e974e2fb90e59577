// SPDX-License-Identifier: MIT
#pragma once
// Jacobi polynomials P_i^{(alpha,beta)} on [-1, 1] (Abramowitz-Stegun convention: alpha belongs to the
// (1 - x) factor of the weight (1 - x)^alpha (1 + x)^beta), their derivatives, norms and roots.
#include <cmath>
#include <cstddef>

namespace jacobid {

// P_i^{(a,b)}(x) by the three-term recurrence (DLMF 18.9.2); stable on [-1, 1].
inline double jacobi_p(int i, double a, double b, double x) noexcept {
    if (i < 0) return 0.0;
    double p_prev = 1.0;
    if (i == 0) return p_prev;
    double p = 0.5 * (a - b) + 0.5 * (a + b + 2.0) * x;
    for (int k = 1; k < i; ++k) {
        const double kk = k;
        const double s = 2.0 * kk + a + b;
        const double c1 = 2.0 * (kk + 1.0) * (kk + a + b + 1.0) * s;
        const double c2 = (s + 1.0) * (a * a - b * b);
        const double c3 = s * (s + 1.0) * (s + 2.0);
        const double c4 = 2.0 * (kk + a) * (kk + b) * (s + 2.0);
        const double p_next = ((c2 + c3 * x) * p - c4 * p_prev) / c1;
        p_prev = p;
        p = p_next;
    }
    return p;
}

// n-th derivative: d^n/dx^n P_i^{(a,b)} = Gamma(i+a+b+1+n) / (2^n Gamma(i+a+b+1)) P_{i-n}^{(a+n,b+n)}.
// The product form avoids Gamma of a non-positive argument (i + a + b + 1 may be <= 0 for i = 0).
inline double jacobi_p_derivative(int i, double a, double b, int n, double x) noexcept {
    if (n > i) return 0.0;
    double factor = 1.0;
    for (int k = 0; k < n; ++k) factor *= 0.5 * (i + a + b + 1.0 + k);
    return factor * jacobi_p(i - n, a + n, b + n, x);
}

// ||P_i^{(a,b)}||^2 = int_{-1}^{1} (1-x)^a (1+x)^b P_i(x)^2 dx, via lgamma (large a, b do not overflow).
inline double jacobi_norm_squared(int i, double a, double b) noexcept {
    const double two_pow = std::exp2(a + b + 1.0);
    if (i == 0) {
        return two_pow * std::exp(std::lgamma(a + 1.0) + std::lgamma(b + 1.0) - std::lgamma(a + b + 2.0));
    }
    const double ii = i;
    return two_pow / (2.0 * ii + a + b + 1.0) *
           std::exp(std::lgamma(ii + a + 1.0) + std::lgamma(ii + b + 1.0) - std::lgamma(ii + a + b + 1.0) -
                    std::lgamma(ii + 1.0));
}

// Largest root of P_i^{(a,b)} (i >= 1). All roots are simple and lie in (-1, 1); in x = cos(theta) they
// are roughly uniformly spaced, so a scan in theta brackets the largest one, then bisection refines it.
inline double jacobi_largest_root(int i, double a, double b) noexcept {
    if (i < 1) return 1.0;
    constexpr int kScan = 8192;
    constexpr double kPi = 3.14159265358979323846;
    double x_hi = 1.0;
    double p_hi = jacobi_p(i, a, b, x_hi);  // P_i(1) > 0
    for (int k = 1; k <= kScan; ++k) {
        const double x_lo = std::cos(kPi * k / kScan);
        const double p_lo = jacobi_p(i, a, b, x_lo);
        if ((p_lo <= 0.0) != (p_hi <= 0.0) || p_lo == 0.0) {
            double lo = x_lo, hi = x_hi;
            for (int it = 0; it < 200 && hi - lo > 1e-16; ++it) {
                const double mid = 0.5 * (lo + hi);
                if ((jacobi_p(i, a, b, mid) > 0.0) == (p_hi > 0.0)) hi = mid; else lo = mid;
            }
            return 0.5 * (lo + hi);
        }
        x_hi = x_lo;
        p_hi = p_lo;
    }
    return -1.0;  // unreachable for valid parameters
}

}  // namespace jacobid
