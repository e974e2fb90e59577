// SPDX-License-Identifier: MIT
// Property tests of kernel design (lib/include/jacobid/kernel.hpp): random parameters within the ranges
// validate() accepts give finite weights, and each kind of invalid parameter is rejected with its own
// KernelStatus (and leaves the kernel undesigned).
//
// "Valid" here is what validate() accepts, with two practical ceilings: kappa, mu <= 300 and
// Ts in [1e-6 s, 10 s]. Beyond them design() can overflow double (see docs/reliability.md, "Kernel
// parameters beyond the tested ranges"): kappa = mu = 600 or (2 / T)^n with Ts = 1e-120 s.
#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>

#include "jacobid/kernel.hpp"
#include "random_kernel_params.hpp"

namespace {

using jacobid::Discretization;
using jacobid::KernelParams;
using jacobid::KernelStatus;
using jacobid::test::kInf;
using jacobid::test::kNaN;
using jacobid::test::RandomParams;

constexpr int kCases = 1500;

// Weights that are non-zero: every design needs degree + 1 of them (TooFewPoints otherwise).
// Independent of the design code: w(tau) = (1 - tau)^mu (1 + tau)^kappa vanishes at an end of the
// window only when that end's exponent is positive.
std::size_t nonzero_weight_points(const KernelParams& p, std::size_t taps) {
    return taps - (p.kappa > 0.0 ? 1 : 0) - (p.mu > 0.0 ? 1 : 0);
}

template <std::size_t Capacity>
void check_random_valid_kernels(std::uint64_t seed) {
    RandomParams r(seed);
    jacobid::Kernel<double, Capacity> kernel;
    int designed = 0;
    for (int i = 0; i < kCases; ++i) {
        const auto taps = static_cast<std::size_t>(r.integer(3, static_cast<int>(Capacity)));
        KernelParams p = r.valid(r.integer(0, jacobid::kMaxOrder), taps);
        if (r.integer(0, 9) == 0) p.q = r.integer(0, jacobid::kMaxDegree - p.order);  // the whole truncation range
        if (r.integer(0, 9) == 0) p.kappa = r.uniform(40.0, 300.0);
        if (r.integer(0, 9) == 0) p.sample_period = r.decades(1.0, 10.0);
        p.window = static_cast<double>(taps - 1) * p.sample_period;
        ASSERT_EQ(jacobid::validate(p, Capacity), KernelStatus::Ok) << "case " << i;
        const KernelStatus s = kernel.design(p);
        // Every design needs q + n + 1 weighted points (the trapezoidal one too, issue 20: it gave weights of
        // 1e8 without them); fewer non-zero ends-excluded points can only mean fewer weighted ones (interior
        // weights may still underflow, so the converse is not checked).
        if (nonzero_weight_points(p, taps) < static_cast<std::size_t>(p.q + p.order + 1)) {
            EXPECT_EQ(s, KernelStatus::TooFewPoints) << "case " << i;
        }
        if (s == KernelStatus::TooFewPoints) {
            // Valid parameters are refused only for lack of weighted points.
            EXPECT_EQ(jacobid::check_weighted_points(p), KernelStatus::TooFewPoints) << "case " << i;
            EXPECT_FALSE(kernel.designed());
            continue;
        }
        ASSERT_EQ(s, KernelStatus::Ok) << "case " << i;
        ++designed;
        ASSERT_EQ(kernel.taps(), taps) << "case " << i;
        double sum_abs = 0.0;
        for (double w : kernel.weights()) {
            ASSERT_TRUE(std::isfinite(w)) << "case " << i << ": n=" << p.order << " kappa=" << p.kappa << " mu=" << p.mu << " q=" << p.q
                                          << " Ts=" << p.sample_period << " taps=" << taps << " xi=" << p.xi;
            sum_abs += std::abs(w);
        }
        // The bound |y| <= sum|w| max|x| that the bank tests rely on must itself be finite.
        ASSERT_TRUE(std::isfinite(sum_abs)) << "case " << i;
        ASSERT_GT(sum_abs, 0.0) << "case " << i;
        EXPECT_TRUE(std::isfinite(kernel.delay_samples()));
    }
    // Many cases must reach the weights, or the test proves little. Every design needs q + n + 1 weighted
    // points, so with a capacity of 8 taps only about a third of the random cases can (497 of 1500).
    EXPECT_GT(designed, kCases / 4);
}

TEST(KernelProperties, RandomValidParametersGiveFiniteWeights) {
    check_random_valid_kernels<8>(1);
    check_random_valid_kernels<64>(2);
    check_random_valid_kernels<512>(3);
}

// One parameter out of range at a time; validate() checks them in the order of KernelStatus, so the
// status names exactly the parameter that is wrong.
TEST(KernelProperties, EachInvalidParameterIsRejectedWithItsStatus) {
    RandomParams r(4);
    for (int i = 0; i < kCases; ++i) {
        const auto taps = static_cast<std::size_t>(r.integer(3, 64));
        KernelParams p = r.valid(r.integer(0, jacobid::kMaxOrder), taps);
        KernelStatus expected = KernelStatus::Ok;
        switch (r.integer(0, 9)) {
            case 0:
                p.order = r.coin() ? r.integer(-100, -1) : r.integer(jacobid::kMaxOrder + 1, 100);
                expected = KernelStatus::InvalidOrder;
                break;
            case 1:
                p.kappa = r.coin() ? -1.0 - r.decades(1e-12, 1e6) : (r.coin() ? kNaN : (r.coin() ? kInf : -1.0));
                expected = KernelStatus::InvalidKappa;
                break;
            case 2:
                p.mu = r.coin() ? -1.0 - r.decades(1e-12, 1e6) : (r.coin() ? kNaN : (r.coin() ? kInf : -1.0));
                expected = KernelStatus::InvalidMu;
                break;
            case 3:
                p.q = r.coin() ? r.integer(-100, -1) : jacobid::kMaxDegree - p.order + r.integer(1, 50);
                expected = KernelStatus::InvalidTruncation;
                break;
            case 4:
                p.sample_period = r.coin() ? -r.decades(1e-9, 1.0) : (r.coin() ? 0.0 : (r.coin() ? kNaN : kInf));
                expected = KernelStatus::InvalidSamplePeriod;
                break;
            case 5:
                p.window = r.coin() ? p.sample_period * r.uniform(-10.0, 1.99) : (r.coin() ? kNaN : -kInf);
                expected = KernelStatus::WindowTooShort;
                break;
            case 6:
                p.xi = r.coin() ? (r.coin() ? 1.0 : -1.0) * (1.0 + r.decades(1e-12, 1e6)) : kNaN;
                expected = KernelStatus::InvalidXi;
                break;
            case 7:
                p.window = p.sample_period * static_cast<double>(r.integer(65, 100000));  // 66+ taps in 64
                expected = KernelStatus::TooManyTaps;
                break;
            case 8:
                p.window = p.sample_period * 1e300;  // must not reach the llround() of the tap count
                expected = KernelStatus::TooManyTaps;
                break;
            default:
                p.window = kInf;
                expected = KernelStatus::WindowTooShort;
                break;
        }
        jacobid::Kernel<double, 64> fresh;
        EXPECT_EQ(fresh.design(p), expected) << "case " << i;
        EXPECT_FALSE(fresh.designed()) << "case " << i;
    }
}

}  // namespace
