// SPDX-License-Identifier: MIT
// Streaming bank: equals batch after the delay, float vs double, alignment, warm-up, zero allocation.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "allocation_counter.hpp"
#include "jacobid/batch_differentiate.hpp"
#include "jacobid/differentiator_bank.hpp"
#include "jacobid/frequency_response.hpp"

namespace {

using jacobid::BankStatus;
using jacobid::KernelParams;
constexpr double kPi = 3.14159265358979323846;

KernelParams params(int n, double window, double ts = 1e-3, double kappa = 6, int q = 2) {
    KernelParams p;
    p.order = n;
    p.kappa = p.mu = kappa;
    p.q = q;
    p.window = window;
    p.sample_period = ts;
    return p;
}

template <int J>
std::array<jacobid::JointFilterConfig, J> config(double wq, double wv, double wa) {
    std::array<jacobid::JointFilterConfig, J> c{};
    for (auto& j : c) j.params = {params(0, wq), params(1, wv), params(2, wa)};
    return c;
}

std::vector<double> test_signal(std::size_t n, unsigned seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> noise(0, 1e-3);
    std::vector<double> x(n);
    for (std::size_t i = 0; i < n; ++i) {
        const double t = static_cast<double>(i) * 1e-3;
        x[i] = std::sin(2 * kPi * 1.3 * t) + 0.3 * std::sin(2 * kPi * 4.1 * t + 0.5) + noise(rng);
    }
    return x;
}

TEST(StreamingBank, EqualsBatchAfterTheCommonDelay) {
    constexpr int J = 2;
    jacobid::DifferentiatorBank<double, J, 512> bank;
    ASSERT_EQ(bank.configure(config<J>(0.1, 0.2, 0.3)).status, BankStatus::Ok);
    EXPECT_EQ(bank.delay_samples(), 150u);  // the acceleration window, 301 taps
    EXPECT_DOUBLE_EQ(bank.delay_seconds(), 0.15);
    const std::size_t n = 3000;
    const auto x0 = test_signal(n, 1), x1 = test_signal(n, 2);
    // Batch references, each with its own (central) alignment.
    std::vector<std::vector<double>> batch(3);
    std::array<std::size_t, 3> offset{};
    for (int c = 0; c < 3; ++c) {
        const auto& k = bank.kernel(0, c);
        batch[c].resize(jacobid::batch_output_size(n, k.taps()));
        ASSERT_EQ(jacobid::differentiate_direct(k.weights(), jacobid::Span<const double>(x0), jacobid::Span<double>(batch[c])),
                  jacobid::BatchStatus::Ok);
        offset[c] = static_cast<std::size_t>(jacobid::batch_offset_samples(k.taps(), 0.0));
    }
    jacobid::BankOutput<double, J> out;
    std::size_t valid = 0;
    for (std::size_t i = 0; i < n; ++i) {
        ASSERT_EQ(bank.step(Eigen::Vector2d(x0[i], x1[i]), Eigen::Vector2d(10.0 * x0[i], -x1[i]), out), BankStatus::Ok);
        EXPECT_EQ(out.valid, i + 1 >= bank.warmup_samples());
        if (!out.valid) continue;
        ++valid;
        const auto m = static_cast<std::size_t>(out.sample_index);  // uint64_t; size_t is 32-bit on armhf
        ASSERT_EQ(m, i - 150);
        EXPECT_NEAR(out.position[0], batch[0][m - offset[0]], 1e-12);
        EXPECT_NEAR(out.velocity[0], batch[1][m - offset[1]], 1e-10);
        EXPECT_NEAR(out.acceleration[0], batch[2][m - offset[2]], 1e-8);
        EXPECT_DOUBLE_EQ(out.torque[0], 10.0 * x0[m]);  // raw torque aligned to the same instant
        EXPECT_DOUBLE_EQ(out.torque[1], -x1[m]);
        EXPECT_DOUBLE_EQ(out.raw_position[0], x0[m]);  // the measured position of the same instant
        EXPECT_DOUBLE_EQ(out.raw_position[1], x1[m]);
    }
    EXPECT_EQ(valid, n - 300);
}

TEST(StreamingBank, EstimatesTrackTheTrueDerivativesOfASinusoid) {
    // A sinusoid well below the cutoff: estimates equal the analytic derivatives at the aligned instant,
    // up to the gain |H(f)| / (2 pi f)^n predicted by the frequency response.
    constexpr int J = 1;
    jacobid::DifferentiatorBank<double, J, 512> bank;
    ASSERT_EQ(bank.configure(config<J>(0.05, 0.2, 0.3)).status, BankStatus::Ok);
    const double f = 2.0, w = 2 * kPi * f;
    const double gain_v = jacobid::fir_response(bank.kernel(0, 1).weights(), 1e-3, f).magnitude / w;
    const double gain_a = jacobid::fir_response(bank.kernel(0, 2).weights(), 1e-3, f).magnitude / (w * w);
    jacobid::BankOutput<double, J> out;
    for (int i = 0; i < 2000; ++i) {
        const double t = i * 1e-3;
        bank.step(Eigen::Matrix<double, 1, 1>(std::sin(w * t)), Eigen::Matrix<double, 1, 1>(0.0), out);
        if (!out.valid) continue;
        const double ta = static_cast<double>(out.sample_index) * 1e-3;
        EXPECT_NEAR(out.velocity[0], gain_v * w * std::cos(w * ta), 1e-9);
        EXPECT_NEAR(out.acceleration[0], -gain_a * w * w * std::sin(w * ta), 1e-7);
    }
    EXPECT_NEAR(gain_v, 1.0, 0.01);  // and at 2 Hz the gain is close to ideal
}

TEST(StreamingBank, FloatAgreesWithDoubleToFloatPrecision) {
    constexpr int J = 1;
    jacobid::DifferentiatorBank<double, J, 512> bd;
    jacobid::DifferentiatorBank<float, J, 512> bf;
    ASSERT_EQ(bd.configure(config<J>(0.1, 0.2, 0.3)).status, BankStatus::Ok);
    ASSERT_EQ(bf.configure(config<J>(0.1, 0.2, 0.3)).status, BankStatus::Ok);
    const auto x = test_signal(2000, 3);
    jacobid::BankOutput<double, J> od;
    jacobid::BankOutput<float, J> of;
    for (double v : x) {
        bd.step(Eigen::Matrix<double, 1, 1>(v), Eigen::Matrix<double, 1, 1>(v), od);
        bf.step(Eigen::Matrix<float, 1, 1>(static_cast<float>(v)), Eigen::Matrix<float, 1, 1>(static_cast<float>(v)), of);
        if (!od.valid) continue;
        // Relative to the scale of each signal (|q| ~ 1, |qd| ~ 10, |qdd| ~ 100) and to sum |w| |x|.
        EXPECT_NEAR(of.position[0], od.position[0], 1e-5);
        EXPECT_NEAR(of.velocity[0], od.velocity[0], 1e-3);
        EXPECT_NEAR(of.acceleration[0], od.acceleration[0], 0.3);
    }
}

TEST(StreamingBank, RejectsInvalidConfigurations) {
    constexpr int J = 2;
    jacobid::DifferentiatorBank<double, J, 256> bank;
    jacobid::BankOutput<double, J> out;
    EXPECT_EQ(bank.step(Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero(), out), BankStatus::NotConfigured);
    auto c = config<J>(0.1, 0.1, 0.2);
    EXPECT_EQ(bank.configure(c).status, BankStatus::Ok);
    c[1].params[2].order = 1;
    auto r = bank.configure(c);
    EXPECT_EQ(r.status, BankStatus::OrderMismatch);
    EXPECT_EQ(r.joint, 1u);
    EXPECT_EQ(r.channel, 2);
    EXPECT_FALSE(bank.configured());
    c = config<J>(0.1, 0.1, 0.2);
    c[0].params[1].kappa = -2;
    r = bank.configure(c);
    EXPECT_EQ(r.status, BankStatus::InvalidKernel);
    EXPECT_EQ(r.kernel_status, jacobid::KernelStatus::InvalidKappa);
    c = config<J>(0.1, 0.1, 0.2);
    c[0].params[1].sample_period = 2e-3;
    EXPECT_EQ(bank.configure(c).status, BankStatus::SamplePeriodMismatch);
    c = config<J>(0.1, 0.101, 0.2);  // 102 taps: delay 50.5 samples cannot be aligned
    EXPECT_EQ(bank.configure(c).status, BankStatus::DelayNotAlignable);
    c = config<J>(0.1, 0.1, 0.3);  // 301 taps > 256
    r = bank.configure(c);
    EXPECT_EQ(r.status, BankStatus::InvalidKernel);
    EXPECT_EQ(r.kernel_status, jacobid::KernelStatus::TooManyTaps);
    c = config<J>(0.25, 0.01, 0.01);  // q^ 251 taps fits, the 0.01 s windows need a lag of 120 + 11 taps: fine
    EXPECT_EQ(bank.configure(c).status, BankStatus::Ok);
    c[0].params[0].window = 0.254;  // delay 127: velocity window 11 taps + lag 122 = 133 fits; still Ok
    EXPECT_EQ(bank.configure(c).status, BankStatus::Ok);
    jacobid::DifferentiatorBank<double, 1, 64> small;
    std::array<jacobid::JointFilterConfig, 1> s{};
    s[0].params = {params(0, 0.062), params(1, 0.062), params(2, 0.062)};  // 63 taps, delay 31: fits
    EXPECT_EQ(small.configure(s).status, BankStatus::Ok);
    s[0].params[0].xi = 1.0;  // causal q^: delay 0; others 31 -> lag 31 for q^: 63 + 31 > 64
    EXPECT_EQ(small.configure(s).status, BankStatus::AlignmentExceedsCapacity);
}

TEST(StreamingBank, NoHeapAllocationIn100000Ticks) {
    constexpr int J = 6;
    using Bank = jacobid::DifferentiatorBank<double, J, 256>;
    static Bank bank;  // large: static storage, as on a controller
    ASSERT_EQ(bank.configure(config<J>(0.21, 0.21, 0.21)).status, BankStatus::Ok);
    jacobid::BankOutput<double, J> out;
    Eigen::Matrix<double, J, 1> q = Eigen::Matrix<double, J, 1>::Zero(), tau = q;
    double checksum = 0;
    const auto before = jacobid::test::allocation_count();
    for (int i = 0; i < 100000; ++i) {
        q.setConstant(std::sin(i * 1e-3));
        bank.step(q, tau, out);
        checksum += out.velocity[5];
    }
    const auto after = jacobid::test::allocation_count();
    EXPECT_EQ(after - before, 0u);
    EXPECT_TRUE(std::isfinite(checksum));
    // The counter itself works: a std::vector allocates.
    const auto probe_before = jacobid::test::allocation_count();
    std::vector<int> v(10);
    EXPECT_GT(jacobid::test::allocation_count(), probe_before);
    EXPECT_EQ(v.size(), 10u);
}

}  // namespace
