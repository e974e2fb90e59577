// SPDX-License-Identifier: MIT
// Central Euler differences. Expected values come from Taylor expansion, not from the code:
//   (x(t+h) - x(t-h)) / 2h       = x'(t) + h^2/6 x'''(t) + ...     (exact up to degree 2)
//   (x(t+h) - 2x(t) + x(t-h))/h^2 = x''(t) + h^2/12 x''''(t) + ... (exact up to degree 3)
#include "jacobid/baseline/euler_difference.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

namespace {

using jacobid::FilterStatus;
using jacobid::Span;

constexpr double kUntouched = 12345.0;

struct Sampled {
    std::vector<double> t;
    std::vector<double> x;
};

Sampled sample(const std::function<double(double)>& f, double t0, double period, std::size_t n) {
    Sampled s;
    for (std::size_t k = 0; k < n; ++k) {
        s.t.push_back(t0 + period * static_cast<double>(k));
        s.x.push_back(f(s.t.back()));
    }
    return s;
}

void expect_valid_range(const jacobid::DifferenceResult& result, std::size_t n) {
    EXPECT_EQ(result.status, FilterStatus::Ok);
    EXPECT_EQ(result.valid.begin, 1u);
    EXPECT_EQ(result.valid.end, n - 1);
}

// Samples outside the valid range must not be invented: they keep what the caller had there.
void expect_ends_untouched(const std::vector<double>& derivative) {
    EXPECT_EQ(derivative.front(), kUntouched);
    EXPECT_EQ(derivative.back(), kUntouched);
}

struct SamplingCase {
    double t0;
    double period;
};

class EulerDifference : public ::testing::TestWithParam<SamplingCase> {};

TEST_P(EulerDifference, FirstDerivativeExactForQuadratics) {
    const SamplingCase c = GetParam();
    const auto quadratic = [](double t) { return 0.75 - 1.5 * t + 2.25 * t * t; };
    const Sampled s = sample(quadratic, c.t0, c.period, 200);
    std::vector<double> dx(s.x.size(), kUntouched);
    expect_valid_range(jacobid::euler_first_derivative(Span<const double>(s.x.data(), s.x.size()), c.period, dx),
                       s.x.size());
    for (std::size_t k = 1; k + 1 < s.x.size(); ++k) {
        // Rounding of the samples is amplified by 1 / (2 Ts); the bound allows for that, nothing more.
        EXPECT_NEAR(dx[k], -1.5 + 4.5 * s.t[k], 1e-11 / c.period) << "k = " << k;
    }
    expect_ends_untouched(dx);
}

TEST_P(EulerDifference, SecondDerivativeExactForCubics) {
    const SamplingCase c = GetParam();
    const auto cubic = [](double t) { return 0.5 + 1.25 * t - 0.75 * t * t + 1.5 * t * t * t; };
    const Sampled s = sample(cubic, c.t0, c.period, 200);
    std::vector<double> ddx(s.x.size(), kUntouched);
    expect_valid_range(jacobid::euler_second_derivative(Span<const double>(s.x.data(), s.x.size()), c.period, ddx),
                       s.x.size());
    for (std::size_t k = 1; k + 1 < s.x.size(); ++k) {
        EXPECT_NEAR(ddx[k], -1.5 + 9.0 * s.t[k], 1e-11 / (c.period * c.period)) << "k = " << k;
    }
    expect_ends_untouched(ddx);
}

// One degree more and the leading Taylor term appears, with exactly the predicted size: this pins the
// stencil (a one-sided difference would have an error of order h, not h^2).
TEST_P(EulerDifference, TruncationErrorOfTheNextDegree) {
    const SamplingCase c = GetParam();
    const double h = c.period;
    const Sampled cube = sample([](double t) { return t * t * t; }, c.t0, h, 50);
    std::vector<double> dx(cube.x.size(), kUntouched);
    jacobid::euler_first_derivative(Span<const double>(cube.x.data(), cube.x.size()), h, dx);
    const Sampled quartic = sample([](double t) { return t * t * t * t; }, c.t0, h, 50);
    std::vector<double> ddx(quartic.x.size(), kUntouched);
    jacobid::euler_second_derivative(Span<const double>(quartic.x.data(), quartic.x.size()), h, ddx);
    for (std::size_t k = 1; k + 1 < cube.x.size(); ++k) {
        const double t = cube.t[k];
        EXPECT_NEAR(dx[k], 3.0 * t * t + h * h, 1e-11 / h) << "k = " << k;                // x''' = 6
        EXPECT_NEAR(ddx[k], 12.0 * t * t + 2.0 * h * h, 1e-11 / (h * h)) << "k = " << k;  // x'''' = 24
    }
}

TEST_P(EulerDifference, InPlaceEqualsOutOfPlace) {
    const SamplingCase c = GetParam();
    const Sampled s = sample([](double t) { return std::sin(3.0 * t) + t; }, c.t0, c.period, 64);
    std::vector<double> dx(s.x.size(), kUntouched);
    std::vector<double> ddx(s.x.size(), kUntouched);
    jacobid::euler_first_derivative(Span<const double>(s.x.data(), s.x.size()), c.period, dx);
    jacobid::euler_second_derivative(Span<const double>(s.x.data(), s.x.size()), c.period, ddx);
    std::vector<double> in_place_first = s.x;
    std::vector<double> in_place_second = s.x;
    jacobid::euler_first_derivative(Span<const double>(in_place_first.data(), in_place_first.size()), c.period,
                                    in_place_first);
    jacobid::euler_second_derivative(Span<const double>(in_place_second.data(), in_place_second.size()), c.period,
                                     in_place_second);
    for (std::size_t k = 1; k + 1 < s.x.size(); ++k) {
        EXPECT_EQ(in_place_first[k], dx[k]);
        EXPECT_EQ(in_place_second[k], ddx[k]);
    }
}

INSTANTIATE_TEST_SUITE_P(Sampling, EulerDifference,
                         ::testing::Values(SamplingCase{0.0, 1e-3},           // the paper's 1 kHz
                                           SamplingCase{-0.3, 1.0 / 1024.0},  // negative times, dyadic period
                                           SamplingCase{2.0, 0.01}));

TEST(EulerDifference, ThreeSamplesGiveOneDifference) {
    const std::vector<double> x = {1.0, 4.0, 9.0};  // t^2 at t = 1, 2, 3
    std::vector<double> dx(3, kUntouched);
    std::vector<double> ddx(3, kUntouched);
    expect_valid_range(jacobid::euler_first_derivative(Span<const double>(x.data(), 3), 1.0, dx), 3);
    expect_valid_range(jacobid::euler_second_derivative(Span<const double>(x.data(), 3), 1.0, ddx), 3);
    EXPECT_EQ(dx, (std::vector<double>{kUntouched, 4.0, kUntouched}));
    EXPECT_EQ(ddx, (std::vector<double>{kUntouched, 2.0, kUntouched}));
}

struct DifferenceFunction {
    const char* name;
    jacobid::DifferenceResult (*apply)(Span<const double>, double, Span<double>);
};

class EulerDifferenceErrors : public ::testing::TestWithParam<DifferenceFunction> {
protected:
    void expect_error(FilterStatus expected, std::size_t x_size, double period, std::size_t out_size) {
        const std::vector<double> x(x_size, 1.0);
        std::vector<double> out(out_size, kUntouched);
        const jacobid::DifferenceResult result = GetParam().apply(Span<const double>(x.data(), x.size()), period, out);
        EXPECT_EQ(result.status, expected);
        EXPECT_EQ(result.valid.begin, result.valid.end);  // nothing valid
        for (double v : out) EXPECT_EQ(v, kUntouched);
    }
};

TEST_P(EulerDifferenceErrors, NonPositiveOrNonFiniteSamplePeriodIsInvalidSampling) {
    for (double period :
         {0.0, -1e-3, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
        expect_error(FilterStatus::InvalidSampling, 10, period, 10);
    }
}

TEST_P(EulerDifferenceErrors, OutputOfOtherSizeIsOutputSizeMismatch) {
    expect_error(FilterStatus::OutputSizeMismatch, 10, 1e-3, 9);
    expect_error(FilterStatus::OutputSizeMismatch, 10, 1e-3, 11);
}

TEST_P(EulerDifferenceErrors, FewerThanThreeSamplesIsSignalTooShort) {
    for (std::size_t n : {0u, 1u, 2u}) expect_error(FilterStatus::SignalTooShort, n, 1e-3, n);
}

INSTANTIATE_TEST_SUITE_P(BothDerivatives, EulerDifferenceErrors,
                         ::testing::Values(DifferenceFunction{"First", &jacobid::euler_first_derivative},
                                           DifferenceFunction{"Second", &jacobid::euler_second_derivative}),
                         [](const ::testing::TestParamInfo<DifferenceFunction>& param_info) {
                             return std::string(param_info.param.name);
                         });

}  // namespace
