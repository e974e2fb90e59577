// SPDX-License-Identifier: MIT
// identify::StreamedJacobiStates computes the Jacobi estimates range by range while the pipeline folds its
// chunks (issue 18: no full-length estimate held). Checked against the plain centered sums written out here
// (ranges at both ends of the log, inside, one sample wide; kernels on the direct and on the FFT path; a
// pinned joint; the Coulomb velocity held at the ends), and the whole pipeline against the held estimates
// of estimate_states + fold_states.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "identify/plan/log_columns.hpp"
#include "identify/pipeline/pipeline.hpp"
#include "identify/pipeline/state_source.hpp"
#include "robot/robot_description.hpp"

namespace jacobid::identify {
namespace {

constexpr double kTs = 1e-3;

std::vector<double> random_kernel(std::size_t taps, std::mt19937& rng) {
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::vector<double> w(taps);
    for (auto& v : w) v = u(rng);
    return w;
}

// Output of the centered FIR w at sample k of x: sum_i w[i] x[k - h + i] (h = half width), or `fill`
// where the kernel does not fit; its magnitude sum_i |w[i] x[k - h + i]| for the tolerance.
std::pair<double, double> centered(const std::vector<double>& w, const std::vector<double>& x, std::size_t k, double fill) {
    const std::size_t h = (w.size() - 1) / 2;
    if (k < h || k + h >= x.size()) return {fill, std::abs(fill)};
    double sum = 0.0, magnitude = 0.0;
    for (std::size_t i = 0; i < w.size(); ++i) {
        sum += w[i] * x[k - h + i];
        magnitude += std::abs(w[i] * x[k - h + i]);
    }
    return {sum, magnitude};
}

TEST(StreamedJacobiStates, EveryWindowEqualsTheCenteredSumsOfTheWholeLog) {
    std::mt19937 rng(3);
    std::normal_distribution<double> noise(0.0, 1.0);
    const std::size_t n = 30'000, first = 150, last = n - 150;
    std::vector<std::vector<double>> q(2, std::vector<double>(n)), tau(q);
    for (std::size_t k = 0; k < n; ++k) {
        q[0][k] = std::sin(1e-3 * static_cast<double>(k)) + 1e-3 * noise(rng);
        q[1][k] = 0.3 + 1e-5 * noise(rng);  // stands still: pinned
        tau[0][k] = noise(rng);
        tau[1][k] = 2.0 + noise(rng);
    }
    const LogColumns log = log_columns(q, tau, kTs, "windows", 0.0);
    JacobiKernels kernels;
    kernels.velocity = random_kernel(121, rng);      // long enough for the FFT path on long ranges
    kernels.acceleration = random_kernel(31, rng);   // direct path
    kernels.torque = random_kernel(121, rng);
    kernels.coulomb = {random_kernel(201, rng), random_kernel(11, rng)};
    const JacobiKernels copy = kernels;
    const StreamedJacobiStates states(log, kernels, {true, false}, first, last);
    ASSERT_EQ(states.samples(), n);
    ASSERT_TRUE(states.has_coulomb_velocity());
    ASSERT_EQ(states.torque_fir(), copy.torque);

    double mean = 0.0;
    for (std::size_t k = first; k < last; ++k) mean += q[1][k];
    mean /= static_cast<double>(last - first);
    std::vector<double> coulomb_first(2), coulomb_last(2);
    for (std::size_t j = 0; j < 2; ++j) {
        const std::size_t h = (copy.coulomb[j].size() - 1) / 2;
        coulomb_first[j] = centered(copy.coulomb[j], q[j], h, 0.0).first;
        coulomb_last[j] = centered(copy.coulomb[j], q[j], n - h - 1, 0.0).first;
    }
    ParallelForOptions pool;
    pool.threads = 2;
    StateWindow w;
    for (const auto& range : std::vector<std::pair<std::size_t, std::size_t>>{
             {0, 500}, {100, 20'100}, {n - 300, n}, {5000, 5001}, {0, n}, {40, 60}}) {
        const std::size_t from = range.first, to = range.second;  // named, not bound: lambdas capture them
        states.load(from, to, w, pool);
        ASSERT_EQ(w.from, from);
        ASSERT_EQ(w.to, to);
        for (std::size_t k = from; k < to; ++k) {
            const std::size_t i = k - from;
            auto expect = [&](double actual, std::pair<double, double> expected, const char* what, std::size_t j) {
                ASSERT_LE(std::abs(actual - expected.first), 1e-12 * (1.0 + expected.second))
                    << what << " joint " << j << " sample " << k << " window [" << from << ", " << to << ")";
            };
            expect(w.q[0][i], {q[0][k], 0.0}, "q", 0);
            expect(w.qd[0][i], centered(copy.velocity, q[0], k, 0.0), "qd", 0);
            expect(w.qdd[0][i], centered(copy.acceleration, q[0], k, 0.0), "qdd", 0);
            ASSERT_EQ(w.q[1][i], mean) << k;
            ASSERT_EQ(w.qd[1][i], 0.0) << k;
            ASSERT_EQ(w.qdd[1][i], 0.0) << k;
            for (std::size_t j = 0; j < 2; ++j) {
                expect(w.tau[j][i], centered(copy.torque, tau[j], k, 0.0), "tau", j);
                const std::size_t h = (copy.coulomb[j].size() - 1) / 2;
                const double fill = k < h ? coulomb_first[j] : coulomb_last[j];
                expect(w.qd_coulomb[j][i], centered(copy.coulomb[j], q[j], k, fill), "qd_coulomb", j);
            }
        }
    }
}

TEST(StreamedJacobiStates, ThePipelineEqualsTheOneOnHeldEstimates) {
    // run_pipeline streams the Jacobi estimates; estimate_states + fold_states holds them whole (the path of the
    // Butterworth baseline and of IDIM-IV/DIDIM). Same plan, same rows: the factors agree to rounding (the
    // FFT blocks of the two differ), with the Coulomb velocity on and a joint standing still.
    std::mt19937 rng(5);
    std::normal_distribution<double> noise(0.0, 1.0);
    const std::size_t n = 40'000;
    std::vector<std::vector<double>> q(2, std::vector<double>(n)), tau(q);
    for (std::size_t k = 0; k < n; ++k) {
        const double t = static_cast<double>(k) * kTs;
        q[0][k] = 0.8 * std::sin(2.0 * 3.14159265358979 * 0.4 * t) + 1e-4 * noise(rng);
        q[1][k] = -0.2 + 1e-5 * noise(rng);
        tau[0][k] = 3.0 * std::cos(2.0 * 3.14159265358979 * 0.4 * t) + 0.05 * noise(rng);
        tau[1][k] = 1.5 + 0.05 * noise(rng);
    }
    const LogColumns log = log_columns(q, tau, kTs, "held vs streamed", 0.0);
    const auto model = robot::make_robot_model(robot::default_planar2r_description());
    PipelineSettings s;
    s.bandwidth = 1.0;
    s.chunk = 1000;  // several chunks
    s.coulomb_velocity_ratio = 2.0;
    const PipelineOutput streamed = run_pipeline(*model, log, s);
    PipelineInfo info = plan_pipeline(log, s);
    const StateEstimates held = estimate_states(log, s, info, model.get());
    const PipelineOutput whole = fold_states(*model, log, s, info, held);
    ASSERT_FALSE(streamed.info.joint_moves[1]);
    EXPECT_EQ(streamed.info.velocity_cutoff, whole.info.velocity_cutoff);
    EXPECT_EQ(streamed.info.coulomb_velocity_cutoffs, whole.info.coulomb_velocity_cutoffs);
    ASSERT_EQ(streamed.factors.r.size(), 2u);
    for (std::size_t j = 0; j < 2; ++j) {
        EXPECT_EQ(streamed.factors.rows[j], whole.factors.rows[j]);
        const Eigen::MatrixXd a = streamed.factors.r[j].transpose() * streamed.factors.r[j];
        const Eigen::MatrixXd b = whole.factors.r[j].transpose() * whole.factors.r[j];
        EXPECT_LT((a - b).norm(), 1e-12 * b.norm()) << "joint " << j;
        EXPECT_GT(b.norm(), 0.0);
    }
}

}  // namespace
}  // namespace jacobid::identify
