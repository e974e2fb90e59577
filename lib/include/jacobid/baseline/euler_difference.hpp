// SPDX-License-Identifier: MIT
#pragma once
// Central Euler differences, the paper's baseline differentiator (applied after the forward-backward
// Butterworth filter):
//   first derivative   (x[k+1] - x[k-1]) / (2 Ts)         exact for polynomials of degree <= 2,
//   second derivative  (x[k+1] - 2 x[k] + x[k-1]) / Ts^2   exact for polynomials of degree <= 3.
// The first and the last sample have no central difference. They are not extrapolated: the output
// there is left as it was, and the functions return the index range that holds differences.
#include <cmath>
#include <cstddef>

#include "jacobid/baseline/filter_status.hpp"
#include "jacobid/span.hpp"

namespace jacobid {

// Half-open index range [begin, end) of the output that was written.
struct ValidRange {
    std::size_t begin = 0;
    std::size_t end = 0;
};

struct DifferenceResult {
    FilterStatus status = FilterStatus::Ok;
    ValidRange valid;  // [1, n - 1) on success, empty on error
};

namespace euler_detail {

inline FilterStatus check_difference_request(Span<const double> x, double sample_period,
                                             Span<double> derivative) noexcept {
    if (!(sample_period > 0.0) || !std::isfinite(sample_period)) return FilterStatus::InvalidSampling;
    if (derivative.size() != x.size()) return FilterStatus::OutputSizeMismatch;
    if (x.size() < 3) return FilterStatus::SignalTooShort;
    return FilterStatus::Ok;
}

}  // namespace euler_detail

// dx[k] = (x[k+1] - x[k-1]) / (2 Ts) for k in [1, n-1); dx[0] and dx[n-1] are not written.
// dx.size() must equal x.size(); dx may be x itself (the previous sample is carried in a local).
// Errors, checked in this order: InvalidSampling (Ts not finite and > 0), OutputSizeMismatch,
// SignalTooShort (fewer than 3 samples). Nothing is written on error.
inline DifferenceResult euler_first_derivative(Span<const double> x, double sample_period, Span<double> dx) noexcept {
    const FilterStatus status = euler_detail::check_difference_request(x, sample_period, dx);
    if (status != FilterStatus::Ok) return {status, {}};
    const std::size_t n = x.size();
    const double inverse_span = 1.0 / (2.0 * sample_period);
    double previous = x[0];
    for (std::size_t k = 1; k + 1 < n; ++k) {
        const double current = x[k];
        dx[k] = (x[k + 1] - previous) * inverse_span;
        previous = current;
    }
    return {FilterStatus::Ok, {1, n - 1}};
}

// ddx[k] = (x[k+1] - 2 x[k] + x[k-1]) / Ts^2 for k in [1, n-1); ddx[0] and ddx[n-1] are not written.
// Sizes, aliasing and errors as euler_first_derivative.
inline DifferenceResult euler_second_derivative(Span<const double> x, double sample_period, Span<double> ddx) noexcept {
    const FilterStatus status = euler_detail::check_difference_request(x, sample_period, ddx);
    if (status != FilterStatus::Ok) return {status, {}};
    const std::size_t n = x.size();
    const double inverse_period_squared = 1.0 / (sample_period * sample_period);
    double previous = x[0];
    for (std::size_t k = 1; k + 1 < n; ++k) {
        const double current = x[k];
        ddx[k] = (x[k + 1] - 2.0 * current + previous) * inverse_period_squared;
        previous = current;
    }
    return {FilterStatus::Ok, {1, n - 1}};
}

}  // namespace jacobid
