// SPDX-License-Identifier: MIT
#pragma once
// Frequency response of an FIR differentiator, its -3 dB cutoff relative to the ideal (2 pi f)^n, and the
// inverse design: the window that gives a wanted cutoff.
#include <algorithm>
#include <cmath>
#include <complex>
#include <cstddef>

#include "jacobid/kernel_design.hpp"
#include "jacobid/kernel_params.hpp"
#include "jacobid/span.hpp"

namespace jacobid {

struct FrequencyPoint {
    double frequency = 0.0;    // Hz
    std::complex<double> response{};
    double magnitude = 0.0;    // |H|
    double phase = 0.0;        // arg H in rad, wrapped to (-pi, pi]
    double group_delay = 0.0;  // -d(arg H)/d(omega), seconds
};

// H(f) = sum_j b_j exp(-i 2 pi f Ts j) with b_j = w[L-1-j]: weights are stored oldest first, so the newest
// sample (lag 0) is the last weight.
template <typename Scalar>
FrequencyPoint fir_response(Span<const Scalar> weights, double sample_period, double frequency) noexcept {
    constexpr double kTwoPi = 6.283185307179586476925;
    const std::size_t taps = weights.size();
    const double omega = kTwoPi * frequency * sample_period;  // rad per sample
    std::complex<double> h{}, lag_weighted{};
    for (std::size_t j = 0; j < taps; ++j) {
        const double b = static_cast<double>(weights[taps - 1 - j]);
        const std::complex<double> e = std::polar(1.0, -omega * static_cast<double>(j));
        h += b * e;
        lag_weighted += static_cast<double>(j) * b * e;
    }
    FrequencyPoint p;
    p.frequency = frequency;
    p.response = h;
    p.magnitude = std::abs(h);
    p.phase = std::arg(h);
    // d/domega of arg H = Im(H'/H), H' = -i sum j b_j e^{-i omega j}  =>  group delay = Re(sum j b e / H).
    p.group_delay = (p.magnitude > 0.0 ? std::real(lag_weighted / h) : 0.0) * sample_period;
    return p;
}

// Magnitude of the ideal n-th order differentiator, (2 pi f)^n.
inline double ideal_magnitude(int order, double frequency) noexcept {
    return std::pow(6.283185307179586476925 * frequency, order);
}

struct Cutoff {
    bool found = false;     // false: |H| stays within 3 dB of the ideal up to Nyquist
    double frequency = 0.0;  // Hz
};

// First frequency where |H(f)| falls 3 dB below (2 pi f)^n, found numerically: a scan in steps of
// 1 / (40 T) (finer than any feature of a window-T filter's passband) brackets it, bisection refines it.
template <typename Scalar>
Cutoff find_cutoff(Span<const Scalar> weights, double sample_period, int order) noexcept {
    const double nyquist = 0.5 / sample_period;
    const double span = static_cast<double>(weights.size() > 1 ? weights.size() - 1 : 1) * sample_period;
    const double step = 1.0 / (40.0 * span);
    const double threshold = 1.0 / std::sqrt(2.0);
    auto ratio = [&](double f) { return fir_response(weights, sample_period, f).magnitude / ideal_magnitude(order, f); };
    double lo = 0.0;
    for (double f = step; f <= nyquist; f += step) {
        if (ratio(f) < threshold) {
            double hi = f;
            for (int it = 0; it < 60; ++it) {
                const double mid = 0.5 * (lo + hi);
                if (ratio(mid) < threshold) hi = mid; else lo = mid;
            }
            return {true, 0.5 * (lo + hi)};
        }
        lo = f;
    }
    if (ratio(nyquist) < threshold) return {true, nyquist};
    return {false, nyquist};
}

struct WindowDesign {
    KernelStatus status = KernelStatus::Ok;
    double window = 0.0;  // T in seconds, a whole number of sample periods
    double cutoff = 0.0;  // the cutoff actually achieved, Hz
};

// The window T (a whole number of samples) whose kernel has its cutoff closest to `wanted_cutoff`, for the
// other parameters of `base`. With odd_taps the tap count stays odd (integer central delay, needed to align
// central estimates with raw samples). `scratch` holds one kernel (its size bounds T).
//
// Short kernels (a few tens of taps, e.g. at 100 Hz) do not follow the continuous-time law cutoff ~ 1/T
// closely and their cutoff need not decrease monotonically with the tap count, so every tap count up to
// kExhaustiveTaps is tried. Longer kernels follow the law well: a first guess from it is refined by
// stepping the tap count while the error shrinks.
inline WindowDesign window_for_cutoff(KernelParams base, double wanted_cutoff, bool odd_taps, Span<double> scratch) noexcept {
    constexpr std::size_t kExhaustiveTaps = 101;
    WindowDesign result;
    const double ts = base.sample_period;
    if (!(wanted_cutoff > 0.0) || !std::isfinite(wanted_cutoff)) {
        result.status = KernelStatus::WindowTooShort;
        return result;
    }
    const std::size_t step = odd_taps ? 2 : 1;
    KernelStatus status = KernelStatus::Ok;
    double best_error = 1e300;
    std::size_t best_taps = 0;
    double best_cutoff = 0.0;
    // Designs the kernel of `taps` taps, returns its cutoff (0 when the design fails, see `status`) and
    // keeps the best candidate so far.
    auto evaluate = [&](std::size_t taps) {
        KernelParams p = base;
        p.window = static_cast<double>(taps - 1) * ts;
        status = design_kernel(p, scratch);
        if (status != KernelStatus::Ok) return 0.0;
        const double c = find_cutoff(Span<const double>(scratch.data(), taps), ts, p.order).frequency;
        if (std::abs(c - wanted_cutoff) < best_error) {
            best_error = std::abs(c - wanted_cutoff);
            best_taps = taps;
            best_cutoff = c;
        }
        return c;
    };
    // Exhaustive over short kernels (cheap: at most 50 designs of <= 101 taps).
    double longest_short_cutoff = 0.0;
    for (std::size_t taps = 3; taps <= std::min(kExhaustiveTaps, scratch.size()); taps += step) {
        const double c = evaluate(taps);
        if (status == KernelStatus::TooFewPoints) continue;  // not enough weighted samples yet
        if (status != KernelStatus::Ok) {
            result.status = status;
            return result;
        }
        longest_short_cutoff = c;
    }
    const bool needs_longer = longest_short_cutoff > wanted_cutoff;
    if (needs_longer && scratch.size() > kExhaustiveTaps) {
        // First guess from the 1/T law at the longest short kernel, then walk while the error shrinks.
        const double product = longest_short_cutoff * static_cast<double>(kExhaustiveTaps - 1) * ts;  // 101: odd
        std::size_t taps = static_cast<std::size_t>(std::llround(std::max(product / (wanted_cutoff * ts) + 1.0, static_cast<double>(kExhaustiveTaps))));
        if (odd_taps && taps % 2 == 0) ++taps;
        if (taps > scratch.size()) {
            result.status = KernelStatus::TooManyTaps;
            return result;
        }
        for (int direction : {+1, -1}) {
            double previous_error = 1e300;
            for (std::size_t t = taps; t > kExhaustiveTaps && t <= scratch.size(); t = direction > 0 ? t + step : t - step) {
                const double error = std::abs(evaluate(t) - wanted_cutoff);
                if (status != KernelStatus::Ok || error > previous_error) break;
                previous_error = error;
            }
        }
    }
    if (best_taps == 0) {
        result.status = status == KernelStatus::Ok ? KernelStatus::TooManyTaps : status;
        return result;
    }
    result.window = static_cast<double>(best_taps - 1) * ts;
    result.cutoff = best_cutoff;
    return result;
}

}  // namespace jacobid
