// SPDX-License-Identifier: MIT
// Property tests of the streaming differentiator bank (lib/include/jacobid/differentiator_bank.hpp):
//  - random valid, alignable configurations configure, and bounded finite input gives finite output
//    within the FIR bound |y| <= sum_k |w_k| * max|x| (a dot product of the window with the weights);
//    the bound is sharp, so an input with the signs of the weights must reach it;
//  - the exact discretization reproduces a quadratic and its derivatives (an exactness property that
//    does not depend on the design code: polynomial of degree <= q + n);
//  - each kind of invalid configuration is rejected with its BankStatus, naming the joint and channel,
//    and a rejected bank refuses to step (NotConfigured).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>

#include "jacobid/differentiator_bank.hpp"
#include "random_kernel_params.hpp"

namespace {

using jacobid::BankStatus;
using jacobid::Discretization;
using jacobid::KernelParams;
using jacobid::KernelStatus;
using jacobid::test::kInf;
using jacobid::test::kNaN;
using jacobid::test::RandomParams;

constexpr int kJoints = 2;
constexpr std::size_t kCapacity = 64;
using Bank = jacobid::DifferentiatorBank<double, kJoints, kCapacity>;
using Config = std::array<jacobid::JointFilterConfig, kJoints>;

// An alignable configuration: every channel central (xi = 0, odd tap counts: whole-sample delays) or
// every channel causal (xi = 1, delay 0). Same sample period everywhere; enough taps for the exact design.
Config random_config(RandomParams& r, bool central) {
    Config c{};
    const double ts = r.decades(1e-5, 1e-1);
    const Discretization d = r.coin() ? Discretization::Exact : Discretization::Trapezoidal;
    for (auto& joint : c) {
        for (int n = 0; n < jacobid::kChannelCount; ++n) {
            int taps = 0;
            do {
                taps = r.integer(3 + n, static_cast<int>(kCapacity));
                if (central && taps % 2 == 0) --taps;
            } while (taps < 3 + n);
            KernelParams p = r.valid(n, static_cast<std::size_t>(taps));
            p.sample_period = ts;
            p.window = static_cast<double>(taps - 1) * ts;
            p.xi = central ? 0.0 : 1.0;
            p.discretization = d;
            p.q = std::min(p.q, taps - 3 - n);  // at least q + n + 1 points strictly inside the window
            joint.params[n] = p;
        }
    }
    return c;
}

double sum_abs(const jacobid::Kernel<double, kCapacity>& k) {
    double s = 0.0;
    for (double w : k.weights()) s += std::abs(w);
    return s;
}

TEST(BankProperties, BoundedInputGivesBoundedFiniteOutput) {
    RandomParams r(11);
    constexpr int kConfigs = 300;
    for (int i = 0; i < kConfigs; ++i) {
        const Config config = random_config(r, r.coin());
        Bank bank;
        const jacobid::BankConfigResult result = bank.configure(config);
        ASSERT_EQ(result.status, BankStatus::Ok) << "case " << i << " joint " << result.joint << " channel " << result.channel << ": "
                                                 << jacobid::describe(result.kernel_status);
        // Input: noise of a random amplitude with occasional spikes of the full amplitude, both signs.
        const double amplitude = r.decades(1e-6, 1e6);
        std::array<std::array<double, jacobid::kChannelCount>, kJoints> bound{};
        for (int j = 0; j < kJoints; ++j) {
            for (int c = 0; c < jacobid::kChannelCount; ++c) bound[j][c] = sum_abs(bank.kernel(j, c)) * amplitude;
        }
        Bank::Output out;
        const int steps = static_cast<int>(bank.warmup_samples()) + 50;
        for (int t = 0; t < steps; ++t) {
            Bank::Vector q, tau;
            for (int j = 0; j < kJoints; ++j) {
                q[j] = r.integer(0, 19) == 0 ? (r.coin() ? amplitude : -amplitude) : r.uniform(-amplitude, amplitude);
                tau[j] = r.uniform(-amplitude, amplitude);
            }
            ASSERT_EQ(bank.step(q, tau, out), BankStatus::Ok);
            for (int j = 0; j < kJoints; ++j) {
                const std::array<double, jacobid::kChannelCount> y{out.position[j], out.velocity[j], out.acceleration[j]};
                for (int c = 0; c < jacobid::kChannelCount; ++c) {
                    ASSERT_TRUE(std::isfinite(y[c])) << "case " << i << " step " << t;
                    // Rounding of the dot product: at most taps * eps relative to the bound.
                    ASSERT_LE(std::abs(y[c]), bound[j][c] * (1.0 + 1e-12)) << "case " << i << " step " << t << " channel " << c;
                }
                ASSERT_TRUE(std::isfinite(out.torque[j]) && std::abs(out.torque[j]) <= amplitude);
            }
        }
    }
}

// x_k = M * sign(w) in the kernel's window gives exactly sum|w| * M: the bound above is the least one.
TEST(BankProperties, SignedInputReachesTheBound) {
    RandomParams r(12);
    for (int i = 0; i < 100; ++i) {
        const Config config = random_config(r, false);  // causal: no alignment lag, window = newest taps
        Bank bank;
        ASSERT_EQ(bank.configure(config).status, BankStatus::Ok) << "case " << i;
        const auto& k = bank.kernel(0, jacobid::kVelocity);
        const auto w = k.weights();  // oldest sample first
        const double m = r.decades(1e-3, 1e3);
        Bank::Output out;
        for (std::size_t t = 0; t < w.size(); ++t) {
            Bank::Vector q = Bank::Vector::Constant(w[t] >= 0.0 ? m : -m);
            ASSERT_EQ(bank.step(q, Bank::Vector::Zero(), out), BankStatus::Ok);
        }
        const double expected = sum_abs(k) * m;
        EXPECT_NEAR(out.velocity[0], expected, expected * 1e-12) << "case " << i;
    }
}

// q(t) = a + b t + c t^2: the exact design of degree q + n >= 2 returns q, q' and q'' at the aligned time.
TEST(BankProperties, ExactDiscretizationReproducesQuadratics) {
    RandomParams r(13);
    int checked = 0;
    for (int i = 0; i < 200; ++i) {
        Config config = random_config(r, r.coin());
        for (auto& joint : config) {
            for (auto& p : joint.params) {
                p.discretization = Discretization::Exact;
                p.kappa = r.uniform(0.0, 8.0);  // moderate exponents: well-conditioned least squares
                p.mu = r.uniform(0.0, 8.0);
                const int taps = static_cast<int>(std::llround(p.window / p.sample_period)) + 1;
                p.q = std::max(0, std::min(2 - p.order + r.integer(0, 2), taps - 3 - p.order));
            }
        }
        bool degree_two = true;  // every channel of joint 0 needs degree q + n >= 2
        for (const KernelParams& p : config[0].params) degree_two = degree_two && p.q + p.order >= 2;
        if (!degree_two) continue;
        Bank bank;
        ASSERT_EQ(bank.configure(config).status, BankStatus::Ok) << "case " << i;
        const double ts = config[0].params[0].sample_period;
        const double a = r.uniform(-1.0, 1.0), b = r.uniform(-1.0, 1.0) / ts / 100.0, c = r.uniform(-1.0, 1.0) / (ts * ts) / 1e4;
        Bank::Output out;
        double max_abs_x = 0.0;
        const int steps = static_cast<int>(bank.warmup_samples()) + 5;
        for (int s = 0; s < steps; ++s) {
            const double t = static_cast<double>(s) * ts;
            const double x = a + b * t + c * t * t;
            max_abs_x = std::max(max_abs_x, std::abs(x));
            ASSERT_EQ(bank.step(Bank::Vector::Constant(x), Bank::Vector::Zero(), out), BankStatus::Ok);
        }
        ASSERT_TRUE(out.valid);
        const double te = static_cast<double>(out.sample_index) * ts;
        // Tolerance: rounding in the design and the dot product, relative to the FIR bound sum|w| max|x|.
        const auto tolerance = [&](int channel) { return 1e-10 * sum_abs(bank.kernel(0, channel)) * max_abs_x; };
        EXPECT_NEAR(out.position[0], a + b * te + c * te * te, tolerance(jacobid::kPosition)) << "case " << i;
        EXPECT_NEAR(out.velocity[0], b + 2.0 * c * te, tolerance(jacobid::kVelocity)) << "case " << i;
        EXPECT_NEAR(out.acceleration[0], 2.0 * c, tolerance(jacobid::kAcceleration)) << "case " << i;
        ++checked;
    }
    EXPECT_GT(checked, 50);
}

struct Fault {
    BankStatus status;
    KernelStatus kernel_status = KernelStatus::Ok;
};

// Breaks one channel of one joint (or the alignment) of a valid causal configuration.
Fault break_config(RandomParams& r, Config& c, std::size_t j, int ch) {
    KernelParams& p = c[j].params[ch];
    switch (r.integer(0, 8)) {
        case 0: p.order = (ch + r.integer(1, 3)) % 4; return {BankStatus::OrderMismatch};
        case 1:
            if (j == 0 && ch == 0) {  // the bank's sample period is channel 0's: change every other one
                for (auto& joint : c)
                    for (auto& q : joint.params) q.sample_period *= 2.0, q.window *= 2.0;
                p.sample_period /= 2.0;
                p.window /= 2.0;
                return {BankStatus::SamplePeriodMismatch};  // reported at joint 0, channel 1
            }
            p.sample_period *= 1.0 + r.decades(1e-12, 1.0);
            return {BankStatus::SamplePeriodMismatch};
        case 2: p.kappa = r.coin() ? kNaN : -1.0 - r.decades(1e-9, 10.0); return {BankStatus::InvalidKernel, KernelStatus::InvalidKappa};
        case 3: p.mu = r.coin() ? kInf : -1.0; return {BankStatus::InvalidKernel, KernelStatus::InvalidMu};
        case 4: p.q = r.coin() ? -1 : jacobid::kMaxDegree - ch + 1; return {BankStatus::InvalidKernel, KernelStatus::InvalidTruncation};
        case 5: p.window = p.sample_period * r.uniform(0.0, 1.9); return {BankStatus::InvalidKernel, KernelStatus::WindowTooShort};
        case 6: p.xi = r.coin() ? kNaN : 1.5; return {BankStatus::InvalidKernel, KernelStatus::InvalidXi};
        case 7: p.window = p.sample_period * static_cast<double>(kCapacity + 1); return {BankStatus::InvalidKernel, KernelStatus::TooManyTaps};
        default:
            // A central channel with an even tap count has a half-sample delay: not alignable.
            p.xi = 0.0;
            p.window = p.sample_period * static_cast<double>(2 * r.integer(3, 20) - 1);  // taps - 1 odd, taps >= 6
            p.q = 0;                                                                       // enough points
            return {BankStatus::DelayNotAlignable};
    }
}

TEST(BankProperties, EachInvalidConfigurationIsRejectedWithItsStatus) {
    RandomParams r(14);
    for (int i = 0; i < 1000; ++i) {
        Config config = random_config(r, false);
        const auto j = static_cast<std::size_t>(r.integer(0, kJoints - 1));
        const int ch = r.integer(0, jacobid::kChannelCount - 1);
        const Fault fault = break_config(r, config, j, ch);
        Bank bank;
        const jacobid::BankConfigResult result = bank.configure(config);
        ASSERT_EQ(result.status, fault.status) << "case " << i << ": " << jacobid::describe(result.status) << ", expected "
                                               << jacobid::describe(fault.status) << " (" << jacobid::describe(fault.kernel_status) << ")";
        if (fault.status == BankStatus::InvalidKernel) {
            EXPECT_EQ(result.kernel_status, fault.kernel_status) << "case " << i;
        }
        if (fault.status != BankStatus::DelayNotAlignable && !(fault.status == BankStatus::SamplePeriodMismatch && j == 0 && ch == 0)) {
            EXPECT_EQ(result.joint, j) << "case " << i;
            EXPECT_EQ(result.channel, ch) << "case " << i;
        }
        EXPECT_FALSE(bank.configured());
        Bank::Output out;
        EXPECT_EQ(bank.step(Bank::Vector::Zero(), Bank::Vector::Zero(), out), BankStatus::NotConfigured) << "case " << i;
    }
}

// A causal channel of t taps beside a central one delayed by D samples needs t + D slots of history.
TEST(BankProperties, AlignmentBeyondTheCapacityIsRejected) {
    RandomParams r(15);
    for (int i = 0; i < 200; ++i) {
        Config config = random_config(r, false);
        const int central_taps = 2 * r.integer(5, 31) + 1;  // 11..63, delay (taps - 1) / 2
        const int delay = (central_taps - 1) / 2;
        const int causal_taps = r.integer(5, static_cast<int>(kCapacity));
        for (auto& joint : config) {
            KernelParams& central = joint.params[jacobid::kAcceleration];
            central.xi = 0.0;
            central.window = central.sample_period * (central_taps - 1);
            KernelParams& causal = joint.params[jacobid::kVelocity];
            causal.window = causal.sample_period * (causal_taps - 1);
            causal.q = std::min(causal.q, causal_taps - 4);
            joint.params[jacobid::kPosition].xi = 0.0;
            joint.params[jacobid::kPosition].window = joint.params[jacobid::kPosition].sample_period * 2.0;  // 3 taps, delay 1
            joint.params[jacobid::kPosition].q = 0;
        }
        Bank bank;
        const BankStatus s = bank.configure(config).status;
        // Expected from the tap counts alone; the position channel (3 taps, lag D - 1) always fits.
        const BankStatus expected = causal_taps + delay > static_cast<int>(kCapacity) ? BankStatus::AlignmentExceedsCapacity : BankStatus::Ok;
        EXPECT_EQ(s, expected) << "case " << i << ": causal " << causal_taps << " taps, delay " << delay;
    }
}

}  // namespace
