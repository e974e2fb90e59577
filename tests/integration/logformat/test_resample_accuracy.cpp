// SPDX-License-Identifier: MIT
// Non-uniform sampling (docs/method.md, "Non-uniform sampling"): a sum of sines sampled on a UR10e-like
// clock (10/12 ms steps, occasional 2 ms steps, values rounded to 1e-4) is differentiated (a) after cubic
// spline resampling, (b) after linear resampling, (c) with Jacobi weights for the actual sample times, and
// compared with the analytic derivatives; (u) is the same signal sampled uniformly, the floor any method
// can reach. The table printed here is the one in docs/method.md.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "io/nonuniform_jacobi.hpp"
#include "io/resample.hpp"
#include "jacobid/kernel_design.hpp"

namespace {

using jacobid::KernelParams;
using jacobid::io::Interpolation;
using jacobid::io::UniformGrid;

constexpr double kPi = 3.14159265358979323846;
const double kFreq[] = {0.3, 0.7, 1.3, 2.1};
const double kAmp[] = {0.5, 0.3, 0.2, 0.1};
const double kPhase[] = {0.1, 1.2, 2.3, 0.7};

// n-th derivative of the test signal at t.
double signal(double t, int n) {
    double s = 0.0;
    for (int i = 0; i < 4; ++i) {
        const double w = 2.0 * kPi * kFreq[i];
        s += kAmp[i] * std::pow(w, n) * std::sin(w * t + kPhase[i] + 0.5 * kPi * n);
    }
    return s;
}

double quantize(double v, double step) { return step > 0.0 ? step * std::round(v / step) : v; }

// UR10e-like clock: 10 ms or 12 ms steps (2:1, as in the shared logs), a 2 ms step every ~500 steps.
std::vector<double> ur10e_clock(double duration, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<double> t{0.0};
    while (t.back() < duration) {
        const double r = u(rng);
        t.push_back(t.back() + (r < 0.002 ? 0.002 : r < 0.67 ? 0.010 : 0.012));
    }
    return t;
}

// Central exact Jacobi kernel with an odd tap count on period ts; estimates at grid indices [half, size-half).
std::vector<double> uniform_jacobi(int order, double window, double ts, const std::vector<double>& x, std::size_t& half) {
    half = static_cast<std::size_t>(std::llround(window / (2.0 * ts)));
    KernelParams p;
    p.order = order;
    p.window = 2.0 * static_cast<double>(half) * ts;
    p.sample_period = ts;
    p.discretization = jacobid::Discretization::Exact;
    std::vector<double> c(2 * half + 1);
    EXPECT_EQ(jacobid::design_kernel(p, jacobid::Span<double>(c.data(), c.size())), jacobid::KernelStatus::Ok);
    std::vector<double> out(x.size(), std::nan(""));
    for (std::size_t k = half; k + half < x.size(); ++k) {
        double s = 0.0;
        for (std::size_t j = 0; j < c.size(); ++j) s += c[j] * x[k - half + j];
        out[k] = s;
    }
    return out;
}

// Relative RMS errors of each method: `total` against the analytic derivative, `sampling` against the same
// kernel on the noise-free uniformly sampled signal (the part due to the clock and the rounding, which is
// what the choice between resampling and exact weights changes; the rest is the differentiator's own bias).
struct Errors {
    double uniform, spline, linear, exact;
};
struct Measurement {
    Errors total, sampling;
};

// Relative RMS of `estimate` - `reference` (NaN reference: the analytic derivative) at grid times over the
// central 80 % (away from every window's edge).
double relative_rms(const std::vector<double>& estimate, const std::vector<double>* reference, const UniformGrid& g, int order) {
    double e2 = 0.0, t2 = 0.0;
    const std::size_t from = g.samples / 10, to = g.samples - g.samples / 10;
    for (std::size_t k = from; k < to; ++k) {
        const double truth = signal(g.start + static_cast<double>(k) * g.period, order);
        const double target = reference ? (*reference)[k] : truth;
        e2 += (estimate[k] - target) * (estimate[k] - target);
        t2 += truth * truth;
    }
    return std::sqrt(e2 / t2);
}

Measurement measure(int order, double window, double quantum, unsigned seed) {
    const std::vector<double> t = ur10e_clock(50.0, seed);
    std::vector<double> x(t.size());
    for (std::size_t i = 0; i < t.size(); ++i) x[i] = quantize(signal(t[i], 0), quantum);
    const UniformGrid g = jacobid::io::uniform_grid(t, 0.05);
    std::size_t half = 0;
    std::vector<double> xu(g.samples), clean(g.samples);
    for (std::size_t k = 0; k < g.samples; ++k) {
        clean[k] = signal(g.start + static_cast<double>(k) * g.period, 0);
        xu[k] = quantize(clean[k], quantum);
    }
    const std::vector<double> reference = uniform_jacobi(order, window, g.period, clean, half);
    std::vector<std::vector<double>> estimates;
    estimates.push_back(uniform_jacobi(order, window, g.period, xu, half));
    estimates.push_back(uniform_jacobi(order, window, g.period, jacobid::io::resample(t, x, g, Interpolation::CubicSpline), half));
    estimates.push_back(uniform_jacobi(order, window, g.period, jacobid::io::resample(t, x, g, Interpolation::Linear), half));
    KernelParams p;
    p.order = order;
    p.window = 2.0 * static_cast<double>(half) * g.period;
    std::vector<double> at(g.samples);
    for (std::size_t k = 0; k < g.samples; ++k) at[k] = g.start + static_cast<double>(k) * g.period;
    estimates.push_back(jacobid::io::jacobi_at_sample_times(p, t, x, at));
    double total[4], sampling[4];
    for (std::size_t m = 0; m < 4; ++m) {
        total[m] = relative_rms(estimates[m], nullptr, g, order);
        sampling[m] = relative_rms(estimates[m], &reference, g, order);
    }
    std::printf("| %d | %.2f | %zu | %g | %.2e / %.2e | %.2e / %.2e | %.2e / %.2e | %.2e / %.2e |\n", order, p.window, 2 * half + 1, quantum,
                total[0], sampling[0], total[1], sampling[1], total[2], sampling[2], total[3], sampling[3]);
    return {{total[0], total[1], total[2], total[3]}, {sampling[0], sampling[1], sampling[2], sampling[3]}};
}

TEST(NonUniformSampling, SplineResamplingIsAsAccurateAsExactWeightsOnAUr10eClock) {
    std::printf("| n | T [s] | taps | rounding | uniform | spline | linear | exact weights |  (total / sampling part)\n");
    for (const double quantum : {0.0, 1e-4}) {
        for (const auto& [order, window] : {std::pair{1, 0.1}, std::pair{1, 0.3}, std::pair{2, 0.3}, std::pair{2, 0.6}}) {
            const Measurement e = measure(order, window, quantum, 7);
            // The spline's sampling error stays within 10 % of that of exact weights for the actual times
            // (or below 1e-4 of the signal), and its total error within 1 % of uniform sampling's.
            EXPECT_LT(e.sampling.spline, std::max(1.1 * e.sampling.exact, 1e-4));
            EXPECT_LT(e.total.spline, 1.01 * e.total.uniform + 1e-6);
        }
    }
}

TEST(NonUniformSampling, LinearInterpolationIsMeasurablyWorseWithoutRounding) {
    // Guards the interpolation itself: with linear interpolation the first test's bounds fail.
    const Measurement e = measure(1, 0.1, 0.0, 11);
    EXPECT_GT(e.sampling.linear, 10.0 * e.sampling.spline);
}

TEST(NonUniformSampling, SplineReproducesCubicsExactlyInside) {
    const std::vector<double> t = ur10e_clock(2.0, 3);
    std::vector<double> x(t.size());
    // A natural spline reproduces a straight line exactly and a smooth signal to O(h^4) inside.
    for (std::size_t i = 0; i < t.size(); ++i) x[i] = 0.5 - 2.0 * t[i];
    const UniformGrid g = jacobid::io::uniform_grid(t, 0.05);
    const std::vector<double> y = jacobid::io::resample(t, x, g);
    ASSERT_EQ(y.size(), g.samples);
    for (std::size_t k = 0; k < g.samples; ++k) EXPECT_NEAR(y[k], 0.5 - 2.0 * (g.start + static_cast<double>(k) * g.period), 1e-12);
    for (std::size_t i = 0; i < t.size(); ++i) x[i] = signal(t[i], 0);
    const std::vector<double> s = jacobid::io::resample(t, x, g);
    double worst = 0.0;
    for (std::size_t k = 10; k + 10 < g.samples; ++k) worst = std::max(worst, std::abs(s[k] - signal(g.start + static_cast<double>(k) * g.period, 0)));
    EXPECT_LT(worst, 2e-6);  // h^4 |x''''| / 384 with h = 12 ms, |x''''| ~ 2e3: 1e-7; linear would give ~1e-3
}

}  // namespace
