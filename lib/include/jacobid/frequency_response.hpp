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
// other parameters of `base`. The cutoff of a Jacobi kernel scales as 1/T, so a first guess from one design
// is refined by stepping the tap count. With odd_taps the tap count stays odd (integer central delay,
// needed to align central estimates with raw samples). `scratch` holds one kernel (its size bounds T).
inline WindowDesign window_for_cutoff(KernelParams base, double wanted_cutoff, bool odd_taps, Span<double> scratch) noexcept {
    WindowDesign result;
    const double ts = base.sample_period;
    if (!(wanted_cutoff > 0.0) || !std::isfinite(wanted_cutoff)) {
        result.status = KernelStatus::WindowTooShort;
        return result;
    }
    const std::size_t step = odd_taps ? 2 : 1;
    auto cutoff_at = [&](std::size_t taps, KernelStatus& status) {
        KernelParams p = base;
        p.window = static_cast<double>(taps - 1) * ts;
        status = design_kernel(p, scratch);
        if (status != KernelStatus::Ok) return 0.0;
        const Cutoff c = find_cutoff(Span<const double>(scratch.data(), taps), ts, p.order);
        return c.frequency;
    };
    // First guess from a probe design of moderate length.
    std::size_t probe = std::min<std::size_t>(scratch.size(), 101);
    if (odd_taps && probe % 2 == 0) --probe;
    KernelStatus status;
    const double probe_cutoff = cutoff_at(probe, status);
    if (status != KernelStatus::Ok) {
        result.status = status;
        return result;
    }
    const double product = probe_cutoff * static_cast<double>(probe - 1) * ts;  // ~ constant
    double guess = product / (wanted_cutoff * ts) + 1.0;
    std::size_t taps = static_cast<std::size_t>(std::llround(std::max(guess, 3.0)));
    if (odd_taps && taps % 2 == 0) ++taps;
    if (taps > scratch.size()) {
        result.status = KernelStatus::TooManyTaps;
        return result;
    }
    // Walk in the direction that reduces the error until it grows (cutoff decreases with taps).
    double best_error = 1e300;
    std::size_t best_taps = taps;
    double best_cutoff = 0.0;
    for (int direction : {+1, -1}) {
        for (std::size_t t = taps; t >= 3 && t <= scratch.size(); t = direction > 0 ? t + step : t - step) {
            const double c = cutoff_at(t, status);
            if (status != KernelStatus::Ok) break;
            const double error = std::abs(c - wanted_cutoff);
            if (error < best_error) {
                best_error = error;
                best_taps = t;
                best_cutoff = c;
            } else if (t != taps) {
                break;
            }
        }
    }
    result.window = static_cast<double>(best_taps - 1) * ts;
    result.cutoff = best_cutoff;
    return result;
}

}  // namespace jacobid
