// SPDX-License-Identifier: MIT
#pragma once
// Parameters of one Jacobi differentiator and their validation. Config only: no storage, no maths.
#include <cmath>
#include <cstddef>

namespace jacobid {

enum class Discretization {
    Trapezoidal,  // c_k = g(tau_k) * dtau, halved at the window ends (the paper's choice)
    Exact,        // discrete weighted least squares: exact for polynomials of degree <= q + n on the grid
};

struct KernelParams {
    int order = 1;             // n: derivative order, 0..kMaxOrder
    double kappa = 6.0;        // weight exponent of (1 + tau): shapes the oldest end of the window
    double mu = 6.0;           // weight exponent of (1 - tau): shapes the newest end
    int q = 2;                 // truncation order; polynomial degree N = q + n
    double window = 0.2;       // T = 2h in seconds (rounded to a whole number of sample periods)
    double sample_period = 1e-3;  // Ts in seconds
    double xi = 0.0;           // evaluation point in [-1, 1]: 0 central, 1 causal, in between delayed causal
    Discretization discretization = Discretization::Trapezoidal;
};
// Note on kappa/mu: w(tau) = (1 - tau)^mu (1 + tau)^kappa with tau = +1 the newest sample, so mu shapes
// the newest end of the window and kappa the oldest end (docs/method.md, "Conventions").

constexpr int kMaxOrder = 3;
constexpr int kMaxDegree = 40;  // q + n; far beyond any useful differentiator, bounds fixed-size tables

enum class KernelStatus {
    Ok,
    InvalidOrder,          // n outside 0..kMaxOrder
    InvalidKappa,          // kappa <= -1 or not finite
    InvalidMu,             // mu <= -1 or not finite
    InvalidTruncation,     // q < 0 or q + n > kMaxDegree
    InvalidSamplePeriod,   // Ts <= 0 or not finite
    WindowTooShort,        // T < 2 Ts
    InvalidXi,             // xi outside [-1, 1]
    TooManyTaps,           // round(T / Ts) + 1 exceeds the storage capacity
    TooFewPoints,          // fewer grid points with non-zero weight than polynomial coefficients (any discretization)
    ClosedFormNeedsCentral,  // eq. (12) is the central estimator only
};

inline const char* describe(KernelStatus s) noexcept {
    switch (s) {
        case KernelStatus::Ok: return "ok";
        case KernelStatus::InvalidOrder: return "derivative order must be 0, 1, 2 or 3";
        case KernelStatus::InvalidKappa: return "kappa must be a number in (-1, 300]";
        case KernelStatus::InvalidMu: return "mu must be a number in (-1, 300]";
        case KernelStatus::InvalidTruncation: return "q must be >= 0 and q + order <= 40";
        case KernelStatus::InvalidSamplePeriod: return "sample period must be a finite number >= 1e-9 s";
        case KernelStatus::WindowTooShort: return "window T must be at least 2 sample periods";
        case KernelStatus::InvalidXi: return "xi must lie in [-1, 1]";
        case KernelStatus::TooManyTaps: return "window has more taps (round(T/Ts)+1) than the kernel capacity";
        case KernelStatus::TooFewPoints: return "window has fewer weighted samples than polynomial coefficients (q + order + 1)";
        case KernelStatus::ClosedFormNeedsCentral: return "the closed form (eq. 12) exists for the central estimator (xi = 0) only";
    }
    return "unknown kernel status";
}

// Number of FIR taps: L = round(T / Ts) + 1 (rounded, never truncated: 0.21 / 0.001 is 209.99999...).
inline std::size_t tap_count(const KernelParams& p) noexcept {
    return static_cast<std::size_t>(std::llround(p.window / p.sample_period)) + 1;
}

// Beyond these the design's intermediate terms overflow double and the weights come out NaN while the
// status says Ok (found by the property test, docs/reliability.md): kappa, mu about 550 and up (Beta
// functions and binomials of the exponents), or (2/T)^n for sample periods near 1e-100 s. Weight exponents
// used in practice are below 50; sampling faster than 1 GHz is not a robot joint.
inline constexpr double kMaxWeightExponent = 300.0;
inline constexpr double kMinSamplePeriod = 1e-9;  // s

inline KernelStatus validate(const KernelParams& p, std::size_t capacity) noexcept {
    if (p.order < 0 || p.order > kMaxOrder) return KernelStatus::InvalidOrder;
    if (!std::isfinite(p.kappa) || p.kappa <= -1.0 || p.kappa > kMaxWeightExponent) return KernelStatus::InvalidKappa;
    if (!std::isfinite(p.mu) || p.mu <= -1.0 || p.mu > kMaxWeightExponent) return KernelStatus::InvalidMu;
    if (p.q < 0 || p.q + p.order > kMaxDegree) return KernelStatus::InvalidTruncation;
    if (!std::isfinite(p.sample_period) || p.sample_period < kMinSamplePeriod) return KernelStatus::InvalidSamplePeriod;
    if (!std::isfinite(p.window) || p.window < 2.0 * p.sample_period * (1.0 - 1e-9)) return KernelStatus::WindowTooShort;
    if (!std::isfinite(p.xi) || p.xi < -1.0 || p.xi > 1.0) return KernelStatus::InvalidXi;
    if (p.window / p.sample_period > static_cast<double>(capacity)) return KernelStatus::TooManyTaps;
    if (tap_count(p) > capacity) return KernelStatus::TooManyTaps;
    return KernelStatus::Ok;
}

// Delay of the estimate behind the newest sample: h (1 - xi), in samples of the actual (rounded) grid.
inline double delay_samples(const KernelParams& p) noexcept {
    return 0.5 * static_cast<double>(tap_count(p) - 1) * (1.0 - p.xi);
}

}  // namespace jacobid
