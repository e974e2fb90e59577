// SPDX-License-Identifier: MIT
#pragma once
// FIR weights of the Jacobi differentiator, written oldest sample first into caller-owned storage.
//
// Three constructions (docs/method.md, "Three constructions"):
//  - projection form, trapezoidal: c_k = s_k * g(tau_k), g from the weighted least-squares projection on
//    Jacobi polynomials (any xi);
//  - closed form of the paper's eq. (12), trapezoidal, central only: an independent construction used to
//    check the first (Rodrigues' formula + n integrations by parts, no Jacobi recurrence);
//  - exact: the discrete weighted least-squares fit on the sample grid, in a basis of discrete orthogonal
//    polynomials built by the Stieltjes procedure (never a Vandermonde matrix), exact for polynomials of
//    degree <= q + n on the grid.
// No allocation: every table is a fixed-size std::array bounded by kMaxDegree.
#include <array>
#include <cmath>
#include <cstddef>

#include "jacobid/jacobi_polynomial.hpp"
#include "jacobid/kernel_params.hpp"
#include "jacobid/span.hpp"

namespace jacobid {
namespace detail {

// Position of tap k on the window grid tau_k = -1 + 2k/(L-1); tau = +1 is the newest sample.
inline double grid_tau(std::size_t k, std::size_t taps) noexcept {
    return -1.0 + 2.0 * static_cast<double>(k) / static_cast<double>(taps - 1);
}

// One factor (1 +- tau)^e of the weight at a grid point whose distance to that factor's zero is d.
// At the window end (d = 0) a negative exponent makes the weight infinite; there the mean of the factor
// over the half cell [0, dtau/2], (dtau/2)^e / (e + 1), replaces it (product trapezoid), which keeps the
// quadrature finite and consistent.
inline double weight_factor(double d, double exponent, double dtau) noexcept {
    if (d > 0.0) return std::pow(d, exponent);
    if (exponent > 0.0) return 0.0;
    if (exponent == 0.0) return 1.0;
    return std::pow(0.5 * dtau, exponent) / (exponent + 1.0);
}

// Quadrature weight s_k = w(tau_k) * dtau, halved at both ends (trapezoidal rule).
inline double quadrature_weight(std::size_t k, std::size_t taps, double kappa, double mu) noexcept {
    const double dtau = 2.0 / static_cast<double>(taps - 1);
    const double tau = grid_tau(k, taps);
    const double d_old = (k == 0) ? 0.0 : 1.0 + tau;
    const double d_new = (k + 1 == taps) ? 0.0 : 1.0 - tau;
    const double end_factor = (k == 0 || k + 1 == taps) ? 0.5 : 1.0;
    return weight_factor(d_new, mu, dtau) * weight_factor(d_old, kappa, dtau) * dtau * end_factor;
}

// 1 / h^n with h the half window of the actual (rounded) grid.
inline double derivative_scale(const KernelParams& p, std::size_t taps) noexcept {
    const double h = 0.5 * static_cast<double>(taps - 1) * p.sample_period;
    return std::pow(h, -p.order);
}

// Generalized binomial coefficient C(x, m) for real x and integer m >= 0.
inline double binomial(double x, int m) noexcept {
    double c = 1.0;
    for (int j = 0; j < m; ++j) c *= (x - j) / (j + 1.0);
    return c;
}

// x (x - 1) ... (x - m + 1)
inline double falling_factorial(double x, int m) noexcept {
    double f = 1.0;
    for (int j = 0; j < m; ++j) f *= x - j;
    return f;
}

// P_i^{(a,b)}(0) from the explicit sum (paper, Sec. III-A), independent of the recurrence.
inline double jacobi_p_at_zero_explicit(int i, double a, double b) noexcept {
    double s = 0.0;
    for (int j = 0; j <= i; ++j) {
        s += binomial(i + a, j) * binomial(i + b, i - j) * std::pow(-0.5, i - j) * std::pow(0.5, j);
    }
    return s;
}

// rho_{n,k,m}(tau) / ((1 - tau)^mu (1 + tau)^kappa) with k = kappa + dk, m = mu + dm: the q = 0 (minimal)
// estimator kernel with shifted exponents, divided by the common weight so that only integer powers remain.
//   rho_{n,k,m}(tau) = (-1)^n Gamma(2n+k+m+2) / (2^(2n+k+m+1) Gamma(n+k+1) Gamma(n+m+1))
//                      * d^n/dtau^n [(1 - tau)^(m+n) (1 + tau)^(k+n)]
inline double minimal_kernel_over_weight(int n, double kappa, double mu, int dk, int dm, double tau) noexcept {
    const double k = kappa + dk;
    const double m = mu + dm;
    const double log_c = std::lgamma(2.0 * n + k + m + 2.0) - std::lgamma(n + k + 1.0) - std::lgamma(n + m + 1.0) -
                         (2.0 * n + k + m + 1.0) * std::log(2.0);
    double leibniz = 0.0;  // Leibniz rule, each term divided by (1 - tau)^mu (1 + tau)^kappa
    for (int j = 0; j <= n; ++j) {
        leibniz += binomial(n, j) * ((j % 2) ? -1.0 : 1.0) * falling_factorial(m + n, j) * falling_factorial(k + n, n - j) *
                   std::pow(1.0 - tau, dm + n - j) * std::pow(1.0 + tau, dk + j);
    }
    return ((n % 2) ? -1.0 : 1.0) * std::exp(log_c) * leibniz;
}

}  // namespace detail

// Grid points of a valid `p` with a non-zero quadrature weight (the window ends drop out when kappa or mu > 0).
inline std::size_t weighted_point_count(const KernelParams& p) noexcept {
    const std::size_t taps = tap_count(p);
    std::size_t weighted = 0;
    for (std::size_t k = 0; k < taps; ++k) {
        if (detail::quadrature_weight(k, taps, p.kappa, p.mu) > 0.0) ++weighted;
    }
    return weighted;
}

// TooFewPoints when the window of a valid `p` has fewer weighted samples than the q + n + 1 coefficients of
// its polynomial, for every discretization: the exact fit is then under-determined, and the trapezoidal
// weights no longer approximate the projection at all (order 2, q 2 on 3 taps gave -7.9e7 instead of a
// second difference); Ok otherwise.
inline KernelStatus check_weighted_points(const KernelParams& p) noexcept {
    return weighted_point_count(p) < static_cast<std::size_t>(p.q + p.order) + 1 ? KernelStatus::TooFewPoints : KernelStatus::Ok;
}

// Projection form with the trapezoidal rule (any xi).
inline KernelStatus design_projection_trapezoidal(const KernelParams& p, Span<double> out) noexcept {
    if (const KernelStatus s = validate(p, out.size()); s != KernelStatus::Ok) return s;
    if (const KernelStatus s = check_weighted_points(p); s != KernelStatus::Ok) return s;
    const std::size_t taps = tap_count(p);
    const int n = p.order;
    const int degree = p.q + n;
    // c_i = P_i^(n)(xi) / ||P_i||^2 : the derivative of the projection at xi, per basis polynomial.
    std::array<double, kMaxDegree + 1> coefficient{};
    for (int i = n; i <= degree; ++i) {
        coefficient[i] = jacobi_p_derivative(i, p.mu, p.kappa, n, p.xi) / jacobi_norm_squared(i, p.mu, p.kappa);
    }
    const double scale = detail::derivative_scale(p, taps);
    for (std::size_t k = 0; k < taps; ++k) {
        const double tau = detail::grid_tau(k, taps);
        double g = 0.0;
        for (int i = n; i <= degree; ++i) g += coefficient[i] * jacobi_p(i, p.mu, p.kappa, tau);
        out[k] = scale * detail::quadrature_weight(k, taps, p.kappa, p.mu) * g;
    }
    return KernelStatus::Ok;
}

// Closed form of eq. (12) (Liu, Gibaru, Perruquetti 2011), trapezoidal, central estimator:
//   Q(tau) = sum_{i=0..q} P_i^{(mu+n,kappa+n)}(0) sum_{j=0..i} (-1)^(i+j) C(i,j)
//            (2i+kappa+mu+2n+1)/(i+kappa+mu+2n+1) rho_{n, kappa+j, mu+i-j}(tau)
// The paper's text prints rho_{n,kappa+i-j,mu+j}; with tau = +1 the newest sample (our convention) the
// shifts are mirrored, which is what reproduces the projection form for kappa != mu.
inline KernelStatus design_closed_form_trapezoidal(const KernelParams& p, Span<double> out) noexcept {
    if (const KernelStatus s = validate(p, out.size()); s != KernelStatus::Ok) return s;
    if (p.xi != 0.0) return KernelStatus::ClosedFormNeedsCentral;
    if (const KernelStatus s = check_weighted_points(p); s != KernelStatus::Ok) return s;
    const std::size_t taps = tap_count(p);
    const int n = p.order;
    const double scale = detail::derivative_scale(p, taps);
    std::array<double, kMaxDegree + 1> p_at_zero{};
    for (int i = 0; i <= p.q; ++i) p_at_zero[i] = detail::jacobi_p_at_zero_explicit(i, p.mu + n, p.kappa + n);
    const double s_sum = p.kappa + p.mu + 2.0 * n;
    for (std::size_t k = 0; k < taps; ++k) {
        const double tau = detail::grid_tau(k, taps);
        double q_over_w = 0.0;
        for (int i = 0; i <= p.q; ++i) {
            double inner = 0.0;
            for (int j = 0; j <= i; ++j) {
                const double sign = ((i + j) % 2) ? -1.0 : 1.0;
                inner += sign * detail::binomial(i, j) * (2.0 * i + s_sum + 1.0) / (i + s_sum + 1.0) *
                         detail::minimal_kernel_over_weight(n, p.kappa, p.mu, j, i - j, tau);
            }
            q_over_w += p_at_zero[i] * inner;
        }
        out[k] = scale * detail::quadrature_weight(k, taps, p.kappa, p.mu) * q_over_w;
    }
    return KernelStatus::Ok;
}

// Exact discretization: n-th derivative at xi of the discrete weighted least-squares polynomial of degree
// N = q + n on the grid (weights s_k). Discrete orthogonal polynomials p_i (monic) come from the Stieltjes
// procedure p_{i+1} = (tau - a_i) p_i - b_i p_{i-1}; then c_k = s_k sum_i p_i(tau_k) p_i^(n)(xi) / nu_i.
// Values p_i(tau_k) are re-evaluated from the recurrence per grid point (O(N^2 L)) so no L-sized scratch
// buffer is needed.
inline KernelStatus design_exact(const KernelParams& p, Span<double> out) noexcept {
    if (const KernelStatus s = validate(p, out.size()); s != KernelStatus::Ok) return s;
    const std::size_t taps = tap_count(p);
    const int n = p.order;
    const int degree = p.q + n;
    if (const KernelStatus s = check_weighted_points(p); s != KernelStatus::Ok) return s;

    std::array<double, kMaxDegree + 1> a{}, b{}, nu{};
    // Evaluates p_0..p_upto at tau into values[] using the coefficients found so far.
    auto evaluate = [&](double tau, int upto, std::array<double, kMaxDegree + 1>& values) {
        values[0] = 1.0;
        if (upto >= 1) values[1] = tau - a[0];
        for (int i = 1; i < upto; ++i) values[i + 1] = (tau - a[i]) * values[i] - b[i] * values[i - 1];
    };
    std::array<double, kMaxDegree + 1> values{};
    for (int i = 0; i <= degree; ++i) {
        double norm = 0.0, moment = 0.0;
        for (std::size_t k = 0; k < taps; ++k) {
            const double tau = detail::grid_tau(k, taps);
            evaluate(tau, i, values);
            const double s = detail::quadrature_weight(k, taps, p.kappa, p.mu) * values[i] * values[i];
            norm += s;
            moment += s * tau;
        }
        nu[i] = norm;
        a[i] = moment / norm;
        b[i] = (i == 0) ? 0.0 : norm / nu[i - 1];
    }
    // Derivatives p_i^(m)(xi), m = 0..n, by differentiating the recurrence m times.
    std::array<std::array<double, kMaxDegree + 1>, kMaxOrder + 1> deriv{};
    for (int m = 0; m <= n; ++m) {
        deriv[m][0] = (m == 0) ? 1.0 : 0.0;
        if (degree >= 1) deriv[m][1] = (m == 0) ? p.xi - a[0] : (m == 1 ? 1.0 : 0.0);
        for (int i = 1; i < degree; ++i) {
            deriv[m][i + 1] = (p.xi - a[i]) * deriv[m][i] - b[i] * deriv[m][i - 1] + (m > 0 ? m * deriv[m - 1][i] : 0.0);
        }
    }
    const double scale = detail::derivative_scale(p, taps);
    for (std::size_t k = 0; k < taps; ++k) {
        const double tau = detail::grid_tau(k, taps);
        evaluate(tau, degree, values);
        double sum = 0.0;
        for (int i = n; i <= degree; ++i) sum += values[i] * deriv[n][i] / nu[i];
        out[k] = scale * detail::quadrature_weight(k, taps, p.kappa, p.mu) * sum;
    }
    return KernelStatus::Ok;
}

// The kernel the parameters ask for: projection form (trapezoidal) or exact.
inline KernelStatus design_kernel(const KernelParams& p, Span<double> out) noexcept {
    return p.discretization == Discretization::Exact ? design_exact(p, out) : design_projection_trapezoidal(p, out);
}

// The delayed causal evaluation point that cancels the first truncation error term: the largest root of
// P_{q+1}^{(mu+n, kappa+n)} (docs/method.md, "Three constructions").
inline double delayed_causal_xi(int order, double kappa, double mu, int q) noexcept {
    return jacobi_largest_root(q + 1, mu + order, kappa + order);
}

}  // namespace jacobid
