// SPDX-License-Identifier: MIT
// Motion bandwidth estimate (identify/plan/bandwidth.hpp, docs/method.md "Motion bandwidth estimate") against
// references computed from the signal's construction, never from the estimator: a sum of sines of known
// amplitudes has its 99 % velocity-energy frequency in closed form, and with a known white position noise
// (Gaussian, or a quantizer of step D: variance D^2 / 12) the noise-limited bandwidth is closed form too.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "identify/plan/bandwidth.hpp"

namespace {

using jacobid::identify::BandwidthEstimate;
using jacobid::identify::estimate_bandwidth;
using jacobid::identify::estimate_motion_bandwidth;
using jacobid::identify::estimate_torque_bandwidth;
using jacobid::identify::kAccelerationNoiseShare;
using jacobid::identify::TorqueBandwidth;

struct Sine {
    double amplitude, frequency, phase;
};
// Velocity energies (A 2 pi f)^2 / 2 in the ratio 0.09 : 0.078 : 0.023 : 0.0056: cumulative 46 %, 86 %,
// 97.3 %, 100 %, so 99 % of the velocity energy is reached only by the 2.5 Hz line.
const std::vector<Sine> kSines = {{1.0, 0.3, 0.1}, {0.4, 0.7, 1.3}, {0.1, 1.5, 2.0}, {0.03, 2.5, 0.7}};
constexpr double kTrue99 = 2.5;

std::vector<double> sines(double fs, double seconds, const std::vector<Sine>& s = kSines) {
    std::vector<double> q(static_cast<std::size_t>(fs * seconds));
    for (std::size_t k = 0; k < q.size(); ++k) {
        const double t = static_cast<double>(k) / fs;
        for (const auto& c : s) q[k] += c.amplitude * std::sin(2.0 * M_PI * c.frequency * t + c.phase);
    }
    return q;
}

// Bandwidth B at which white position noise of variance `variance` (flat up to fs / 2) holds
// kAccelerationNoiseShare of the acceleration energy below the cutoff 10 B, the cutoff above every line:
// noise variance / (fs / 2) (2 pi)^4 c^5 / 5 = share x sum_i A_i^2 (2 pi f_i)^4 / 2.
double analytic_noise_limit(double variance, double fs) {
    double signal = 0.0;
    for (const auto& c : kSines) signal += 0.5 * std::pow(c.amplitude * std::pow(2.0 * M_PI * c.frequency, 2), 2);
    const double c5 = kAccelerationNoiseShare * signal * 5.0 / (variance / (0.5 * fs) * std::pow(2.0 * M_PI, 4));
    return std::pow(c5, 0.2) / 10.0;
}

BandwidthEstimate estimate(const std::vector<std::vector<double>>& q, double fs) {
    std::vector<const std::vector<double>*> p;
    for (const auto& x : q) p.push_back(&x);
    return estimate_motion_bandwidth(p, 1.0 / fs, {"q1", "q2"});
}

TEST(MotionBandwidth, CleanSinesGiveTheAnalytic99PercentFrequency) {
    const BandwidthEstimate b = estimate({sines(1000.0, 60.0)}, 1000.0);
    ASSERT_TRUE(b.moving);
    EXPECT_NEAR(b.frequency, kTrue99, 2 * b.resolution);
    EXPECT_FALSE(b.noise_limited);
    EXPECT_EQ(b.jumps, 0u);
    ASSERT_EQ(b.joints.size(), 1u);
    EXPECT_TRUE(b.joints[0].used);
    EXPECT_LT(b.joints[0].floor_fraction, 1e-6);
    EXPECT_FALSE(b.description.empty());
}

TEST(MotionBandwidth, WhiteNoiseFloorIsRemovedAndLimitsTheBandwidth) {
    const double fs = 1000.0, sigma = 1e-3;
    std::vector<double> q = sines(fs, 60.0);
    std::mt19937 rng(5);
    std::normal_distribution<double> noise(0.0, sigma);
    for (double& x : q) x += noise(rng);
    const BandwidthEstimate b = estimate({q}, fs);
    ASSERT_TRUE(b.moving);
    // The noise holds a third of the velocity-difference energy (2 sigma^2 against 3.9e-6 rad^2 of motion):
    // without the floor removed, 99 % of the energy lies at hundreds of Hz.
    EXPECT_GT(b.joints[0].floor_fraction, 0.2);
    EXPECT_NEAR(b.energy_frequency, kTrue99, 2 * b.resolution);
    EXPECT_NEAR(b.joints[0].noise_rms, sigma, 0.1 * sigma);
    EXPECT_TRUE(b.noise_limited);
    EXPECT_NEAR(b.frequency, analytic_noise_limit(sigma * sigma, fs), 0.05 * analytic_noise_limit(sigma * sigma, fs));
    EXPECT_NE(b.description.find("noise"), std::string::npos) << b.description;
}

TEST(MotionBandwidth, CoarseQuantizerIsDetectedAndItsFloorRemoved) {
    const double fs = 100.0, step = 0.01;  // the pendubot's second encoder; ~2 steps per sample: white
    std::vector<double> q = sines(fs, 120.0);
    for (double& x : q) x = step * std::round(x / step);
    const BandwidthEstimate b = estimate({q}, fs);
    ASSERT_TRUE(b.moving);
    EXPECT_NEAR(b.joints[0].quantization_step, step, 1e-9);
    EXPECT_NEAR(b.joints[0].noise_rms, step / std::sqrt(12.0), 0.15 * step / std::sqrt(12.0));
    EXPECT_NEAR(b.energy_frequency, kTrue99, 2 * b.resolution);
    const double limit = analytic_noise_limit(step * step / 12.0, fs);
    EXPECT_NEAR(b.frequency, limit, 0.06 * limit);
}

TEST(MotionBandwidth, JumpsAndOutliersAreBreaksNotMotion) {
    const double fs = 1000.0;
    const std::vector<double> clean = sines(fs, 60.0);
    std::vector<double> jumped = clean;
    // Five runs joined end to end: the position shifts by up to 2 rad between two samples.
    const double shifts[] = {2.0, -1.5, 0.9, 1.9, -0.6};
    for (int j = 0; j < 5; ++j) {
        for (std::size_t k = static_cast<std::size_t>((j + 1) * 10'000); k < jumped.size(); ++k) jumped[k] += shifts[j];
    }
    jumped[33'333] += 0.5;  // and one glitch (one sample off)
    const BandwidthEstimate a = estimate({clean}, fs), b = estimate({jumped}, fs);
    EXPECT_EQ(b.jumps, 6u);
    EXPECT_EQ(b.joints[0].jumps, 6u);
    EXPECT_NEAR(b.frequency, a.frequency, b.resolution);
    EXPECT_NE(b.description.find("jump"), std::string::npos) << b.description;
}

TEST(MotionBandwidth, AJointLostInItsNoiseIsNotUsed) {
    const double fs = 100.0;
    const std::vector<double> moving = sines(fs, 120.0);
    // Second joint: a 5 mrad wobble under a 10 mrad quantizer plus noise; its motion is within its noise.
    std::vector<double> still = sines(fs, 120.0, {{0.005, 9.0, 0.0}});
    std::mt19937 rng(3);
    std::normal_distribution<double> noise(0.0, 0.01);
    for (double& x : still) x = 0.01 * std::round((x + noise(rng)) / 0.01);
    const BandwidthEstimate one = estimate({moving}, fs), two = estimate({moving, still}, fs);
    ASSERT_EQ(two.joints.size(), 2u);
    EXPECT_TRUE(two.joints[0].used);
    EXPECT_TRUE(two.joints[1].moving);
    EXPECT_FALSE(two.joints[1].used);
    EXPECT_DOUBLE_EQ(two.frequency, one.frequency);
}

// The joints are estimated on up to `threads` threads, each on its own: the estimate is the same, field by
// field, whatever the thread count (one joint with jumps, one quantized and noisy, one constant).
TEST(MotionBandwidth, ThreadsDoNotChangeTheEstimate) {
    const double fs = 1000.0;
    std::vector<double> jumped = sines(fs, 30.0), still = sines(fs, 30.0, {{0.005, 9.0, 0.0}});
    for (std::size_t k = 12'000; k < jumped.size(); ++k) jumped[k] += 1.5;
    std::mt19937 rng(5);
    std::normal_distribution<double> noise(0.0, 0.01);
    for (double& x : still) x = 0.01 * std::round((x + noise(rng)) / 0.01);
    const std::vector<double> constant(jumped.size(), 0.25), moving = sines(fs, 30.0);
    const std::vector<const std::vector<double>*> q = {&jumped, &still, &constant, &moving};
    const BandwidthEstimate one = estimate_motion_bandwidth(q, 1.0 / fs, {}, 10.0, 0.99, 1);
    for (const int threads : {2, 3, 8}) {
        const BandwidthEstimate many = estimate_motion_bandwidth(q, 1.0 / fs, {}, 10.0, 0.99, threads);
        EXPECT_EQ(many.frequency, one.frequency) << threads;
        EXPECT_EQ(many.description, one.description) << threads;
        EXPECT_EQ(many.jumps, one.jumps) << threads;
        ASSERT_EQ(many.joints.size(), q.size());
        for (std::size_t j = 0; j < q.size(); ++j) {
            EXPECT_EQ(many.joints[j].name, one.joints[j].name);
            EXPECT_EQ(many.joints[j].noise_rms, one.joints[j].noise_rms);
            EXPECT_EQ(many.joints[j].energy_frequency, one.joints[j].energy_frequency);
            EXPECT_EQ(many.joints[j].quantization_step, one.joints[j].quantization_step);
            EXPECT_EQ(many.joints[j].used, one.joints[j].used);
        }
    }
    EXPECT_EQ(one.jumps, 1u);
    EXPECT_FALSE(one.joints[2].moving);
}

// The torque's bandwidth (bandwidth.hpp, docs/method.md "Motion bandwidth estimate", step 5), against
// frequencies worked out from the torque's construction. Torque lines of amplitude 4 / 2 / 0.8 / 0.2 N.m at
// 0.3 / 1.1 / 2.7 / 4.3 Hz hold energies A^2 / 2 = 8 / 2 / 0.32 / 0.02 N.m^2: cumulative 77.4 %, 96.7 %, 99.81 %,
// 100 %, so 99 % is first reached by the 2.7 Hz line. The positions move at 0.2 Hz only.
const std::vector<Sine> kTorqueSines = {{4.0, 0.3, 0.4}, {2.0, 1.1, 2.1}, {0.8, 2.7, 0.9}, {0.2, 4.3, 1.7}};
constexpr double kTorque99 = 2.7;
const std::vector<Sine> kSlowMotion = {{0.5, 0.2, 0.3}};

std::vector<double> with_white_noise(std::vector<double> x, double sigma, unsigned seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> noise(0.0, sigma);
    for (double& v : x) v += noise(rng);
    return x;
}

std::vector<const std::vector<double>*> pointers(const std::vector<std::vector<double>>& x) {
    std::vector<const std::vector<double>*> p;
    for (const auto& v : x) p.push_back(&v);
    return p;
}

TEST(TorqueBandwidth, SinesAboveWhiteNoiseGiveTheHandComputed99PercentFrequency) {
    const double fs = 1000.0, sigma = 0.05;
    const std::vector<std::vector<double>> q = {sines(fs, 60.0, kSlowMotion)};
    const std::vector<std::vector<double>> tau = {with_white_noise(sines(fs, 60.0, kTorqueSines), sigma, 11)};
    const TorqueBandwidth t = estimate_torque_bandwidth(pointers(tau), 1.0 / fs);
    ASSERT_EQ(t.joints.size(), 1u);
    EXPECT_TRUE(t.joints[0].used);
    EXPECT_NEAR(t.frequency, kTorque99, 2 * t.resolution);
    EXPECT_NEAR(t.joints[0].frequency, kTorque99, 2 * t.resolution);
    EXPECT_NEAR(t.joints[0].noise_rms, sigma, 0.1 * sigma);
    EXPECT_NEAR(t.highest, 250.0, t.resolution);  // 0.25 fs: the floor's band starts there
    // identify's bandwidths: the motion's stays the velocity's 0.2 Hz (F_p), the differentiators' is the torque's;
    // the positions are clean (no noise limit).
    const BandwidthEstimate b = estimate_bandwidth(pointers(q), pointers(tau), 1.0 / fs, {"q1"}, {"tau1"});
    EXPECT_NEAR(b.energy_frequency, 0.2, 2 * b.resolution);
    EXPECT_DOUBLE_EQ(b.frequency, b.energy_frequency);
    EXPECT_TRUE(b.torque_wider);
    EXPECT_FALSE(b.noise_limited);
    EXPECT_FALSE(b.torque_noise_limited);
    EXPECT_NEAR(b.differentiator_frequency, kTorque99, 2 * t.resolution);
    EXPECT_NE(b.description.find("torque's energy"), std::string::npos) << b.description;
    // Without the noise, the same line (the floor removed is the noise's, not the signal's).
    const std::vector<std::vector<double>> clean = {sines(fs, 60.0, kTorqueSines)};
    EXPECT_NEAR(estimate_torque_bandwidth(pointers(clean), 1.0 / fs).frequency, kTorque99, 2 * t.resolution);
}

TEST(TorqueBandwidth, WhiteNoiseAloneGivesNoTorqueBandwidth) {
    const double fs = 1000.0;
    const std::vector<std::vector<double>> q = {sines(fs, 60.0, kSlowMotion), sines(fs, 60.0)};
    const std::vector<std::vector<double>> tau = {with_white_noise(std::vector<double>(60'000, 1.5), 0.2, 4),
                                                  with_white_noise(std::vector<double>(60'000, -0.3), 0.01, 5)};
    const TorqueBandwidth t = estimate_torque_bandwidth(pointers(tau), 1.0 / fs);
    ASSERT_EQ(t.joints.size(), 2u);
    EXPECT_TRUE(t.joints[0].moving);
    EXPECT_FALSE(t.joints[0].used);
    EXPECT_FALSE(t.joints[1].used);
    EXPECT_EQ(t.frequency, 0.0);
    const BandwidthEstimate b = estimate_bandwidth(pointers(q), pointers(tau), 1.0 / fs);
    const BandwidthEstimate v = estimate_motion_bandwidth(pointers(q), 1.0 / fs);
    EXPECT_FALSE(b.torque_wider);
    EXPECT_DOUBLE_EQ(b.frequency, v.frequency);
    EXPECT_DOUBLE_EQ(b.differentiator_frequency, v.frequency);
    EXPECT_NE(b.description.find("velocity's band alone"), std::string::npos) << b.description;
}

// Each joint's own band counts: joint 1's torque is a 1 N.m line at 0.5 Hz, joint 2's a 0.07 N.m line at 3 Hz
// (0.49 % of the two joints' energy: summed, 99 % would be reached at 0.5 Hz). Over noises of 0.05 and 0.0035 N.m
// both hold 200 floor variances (used): the widest, 3 Hz. With joint 2's noise at 0.01 N.m its line holds 24.5
// floor variances, under the 100 that count: joint 1's 0.5 Hz.
TEST(TorqueBandwidth, TheWidestJointAboveItsFloorSetsTheBand) {
    const double fs = 1000.0;
    const std::vector<double> a = sines(fs, 60.0, {{1.0, 0.5, 0.2}}), b = sines(fs, 60.0, {{0.07, 3.0, 1.0}});
    const std::vector<std::vector<double>> both = {with_white_noise(a, 0.05, 1), with_white_noise(b, 0.0035, 2)};
    const TorqueBandwidth t = estimate_torque_bandwidth(pointers(both), 1.0 / fs);
    EXPECT_TRUE(t.joints[0].used);
    EXPECT_TRUE(t.joints[1].used);
    EXPECT_NEAR(t.joints[0].frequency, 0.5, 2 * t.resolution);
    EXPECT_NEAR(t.frequency, 3.0, 2 * t.resolution);
    const std::vector<std::vector<double>> lost = {with_white_noise(a, 0.05, 1), with_white_noise(b, 0.01, 2)};
    const TorqueBandwidth l = estimate_torque_bandwidth(pointers(lost), 1.0 / fs);
    EXPECT_FALSE(l.joints[1].used);
    EXPECT_NEAR(l.frequency, 0.5, 2 * t.resolution);
    // Given noise levels (excite's model torque, noise-free) decide the same way as estimated ones.
    const std::vector<std::vector<double>> clean = {a, b};
    const double inf = std::numeric_limits<double>::infinity();
    const TorqueBandwidth given = estimate_torque_bandwidth(pointers(clean), 1.0 / fs, {}, inf, 0.99, 1, {0.05, 0.0035});
    EXPECT_TRUE(given.noise_known);
    EXPECT_NEAR(given.frequency, 3.0, 2 * t.resolution);
    EXPECT_DOUBLE_EQ(given.joints[1].noise_rms, 0.0035);
    EXPECT_NEAR(estimate_torque_bandwidth(pointers(clean), 1.0 / fs, {}, inf, 0.99, 1, {0.05, 0.01}).frequency, 0.5, 2 * t.resolution);
}

// identify aligns a delayed torque by linear interpolation (x[k] <- (1 - a) x[k] + a x[k + 1]), which low-passes its
// noise: at a = 0.5 the floor band 0.25..0.4 fs keeps 10..50 % of it. Told the shift, the estimate reads the noise
// and the band as before the interpolation.
TEST(TorqueBandwidth, AnInterpolatedTorqueKeepsItsFloor) {
    const double fs = 1000.0, sigma = 0.05;
    const std::vector<double> raw = with_white_noise(sines(fs, 60.0, kTorqueSines), sigma, 11);
    std::vector<double> shifted(raw.size());
    for (std::size_t k = 0; k + 1 < raw.size(); ++k) shifted[k] = 0.5 * raw[k] + 0.5 * raw[k + 1];
    shifted.back() = raw.back();
    const std::vector<std::vector<double>> tau = {shifted};
    const double inf = std::numeric_limits<double>::infinity();
    const TorqueBandwidth told = estimate_torque_bandwidth(pointers(tau), 1.0 / fs, {}, inf, 0.99, 1, {}, 3.5);
    EXPECT_NEAR(told.joints[0].noise_rms, sigma, 0.1 * sigma);
    EXPECT_NEAR(told.frequency, kTorque99, 2 * told.resolution);
    const TorqueBandwidth not_told = estimate_torque_bandwidth(pointers(tau), 1.0 / fs);
    EXPECT_LT(not_told.joints[0].noise_rms, 0.7 * sigma);  // what the shift does unless divided out
}

// The position-noise limit still bounds the differentiators: the noisy positions of WhiteNoiseFloorIsRemovedAndLimits
// (limit below their 2.5 Hz) under the 2.7 Hz torque give the limit, and the description says it won.
TEST(TorqueBandwidth, ThePositionNoiseLimitStillBounds) {
    const double fs = 1000.0, sigma = 1e-3;
    const std::vector<std::vector<double>> q = {with_white_noise(sines(fs, 60.0), sigma, 5)};
    const std::vector<std::vector<double>> tau = {with_white_noise(sines(fs, 60.0, kTorqueSines), 0.05, 11)};
    const BandwidthEstimate b = estimate_bandwidth(pointers(q), pointers(tau), 1.0 / fs);
    const double limit = analytic_noise_limit(sigma * sigma, fs);
    EXPECT_TRUE(b.noise_limited);
    EXPECT_TRUE(b.torque_wider);
    EXPECT_TRUE(b.torque_noise_limited);
    EXPECT_NEAR(b.frequency, limit, 0.05 * limit);
    EXPECT_DOUBLE_EQ(b.differentiator_frequency, b.frequency);
    EXPECT_NEAR(b.torque.frequency, kTorque99, 2 * b.torque.resolution);
    EXPECT_NE(b.description.find("limited by the position noise"), std::string::npos) << b.description;
    EXPECT_NE(b.description.find("the position noise holds the differentiators"), std::string::npos) << b.description;
}

// Real data (../shared/realdata/pendubot, README there): Unix time ~5 ms non-uniform, q1, q2 (0.01 rad
// steps); resampled linearly onto 5 ms. With --bandwidth 0.5 / 1 / 2 / 3 Hz the data_06 -> data_08
// validation relative error is 14.8 / 16.9 / 21.3 / 27.3 % (docs/method.md), best below ~1 Hz.
TEST(MotionBandwidth, PendubotCoarseEncoderGivesANoiseLimitedBandwidthBelow1Hz) {
    const std::filesystem::path file = std::filesystem::path(JACOBID_REALDATA_DIR) / "pendubot" / "data_06.csv";
    if (!std::filesystem::exists(file)) GTEST_SKIP() << "../shared/realdata absent (" << file.string() << ")";
    std::ifstream in(file);
    std::vector<double> t, q1, q2;
    for (std::string line; std::getline(in, line);) {
        std::stringstream s(line);
        std::string cell;
        std::vector<double> row;
        while (std::getline(s, cell, ',')) row.push_back(std::stod(cell));
        ASSERT_GE(row.size(), 3u) << line;
        t.push_back(row[0]);
        q1.push_back(row[1]);
        q2.push_back(row[2]);
    }
    ASSERT_GT(t.size(), 1000u);
    const double ts = 0.005;
    std::vector<std::vector<double>> q(2);
    std::size_t i = 0;
    for (double time = t.front(); time <= t.back(); time += ts) {
        while (t[i + 1] < time) ++i;
        const double w = (time - t[i]) / (t[i + 1] - t[i]);
        q[0].push_back(q1[i] + w * (q1[i + 1] - q1[i]));
        q[1].push_back(q2[i] + w * (q2[i + 1] - q2[i]));
    }
    const BandwidthEstimate b = estimate(q, 1.0 / ts);
    ASSERT_TRUE(b.moving);
    EXPECT_GT(b.frequency, 0.5);
    EXPECT_LT(b.frequency, 1.0);
    EXPECT_TRUE(b.noise_limited);
    // The motion itself reaches the 3.6 Hz harmonic (6 x the 0.6 Hz excitation).
    EXPECT_GT(b.energy_frequency, 3.0);
    EXPECT_LT(b.energy_frequency, 6.0);
    EXPECT_TRUE(b.joints[0].used);
    EXPECT_TRUE(b.joints[1].used);
    EXPECT_GT(b.joints[1].noise_rms, b.joints[0].noise_rms);  // the coarse encoder
    std::cout << "pendubot data_06: " << b.description << "\n";
}

}  // namespace
