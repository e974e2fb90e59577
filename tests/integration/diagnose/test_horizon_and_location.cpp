// SPDX-License-Identifier: MIT
// Short-horizon simulation and residual location on data whose answer is known by construction: a
// noise-free simulated log is reproduced by the true model (and not by a wrong one, nor with the wrong
// torque delay); a synthetic residual with a known harmonic and a known velocity-dependent step is located.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "diagnose/decimated_rows.hpp"
#include "diagnose/horizon_simulation.hpp"
#include "diagnose/residual_analysis.hpp"
#include "identify/pipeline/segmented_pipeline.hpp"
#include "robot/planar2r_model.hpp"
#include "sim/simulator.hpp"

namespace jacobid::diagnose {
namespace {

struct Log {
    std::vector<double> q1, q2, tau1, tau2;
    identify::LogColumns columns;
};

Log noise_free_log(const robot::RobotModel& model, const Eigen::VectorXd& x, double torque_delay) {
    sim::SimulationSettings s;
    s.duration = 8.0;
    sim::MeasurementSettings ms;
    ms.encoder_counts_per_rev = 0.0;
    ms.torque_delay = torque_delay;
    sim::MeasurementModel measurement(ms);
    const std::vector<robot::JointDescription> joints{{"j1", "q1", "tau1", -2.5, 2.5}, {"j2", "q2", "tau2", -2.5, 2.5}};
    Log log;
    sim::simulate(model, x, joints, s, measurement, [&](const sim::SimulatedSample& sample) {
        log.q1.push_back(sample.q_measured[0]);
        log.q2.push_back(sample.q_measured[1]);
        log.tau1.push_back(sample.tau_measured[0]);
        log.tau2.push_back(sample.tau_measured[1]);
    });
    log.columns.source = "simulated";
    log.columns.sample_period = 1e-3;
    log.columns.q = {&log.q1, &log.q2};
    log.columns.tau = {&log.tau1, &log.tau2};
    return log;
}

HorizonResult horizons(const robot::RobotModel& model, const Eigen::VectorXd& x, const Log& log, double delay) {
    identify::PipelineSettings s;
    identify::PipelineInfo info = identify::plan_pipeline(log.columns, s);
    const identify::StateEstimates states = identify::estimate_states(log.columns, s, info);
    return simulate_horizons(model, x, log.columns, states, delay, {0.3, 0.5});
}

TEST(HorizonSimulation, TheTrueModelReproducesTheMotionAWrongOneDoesNot) {
    const robot::Planar2RModel model(robot::Planar2RConfig{0.5, {robot::CoulombModel::SmoothAtan, 100.0}, false, false});
    const std::vector<double> table = robot::paper_table2_parameters(model);
    const Eigen::VectorXd x = Eigen::Map<const Eigen::VectorXd>(table.data(), static_cast<Eigen::Index>(table.size()));
    const Log log = noise_free_log(model, x, 0.0);
    const HorizonResult right = horizons(model, x, log, 0.0);
    EXPECT_GT(right.segments, 10u);
    Eigen::VectorXd wrong = x;
    wrong[model.parameter_index("ZZ1R")] *= 1.05;
    wrong[model.parameter_index("ZZ2")] *= 1.2;
    const HorizonResult bad = horizons(model, wrong, log, 0.0);
    for (std::size_t j = 0; j < 2; ++j) {
        EXPECT_LT(right.rms_error[j], 1e-4) << "joint " << j + 1;
        EXPECT_GT(bad.rms_error[j], 10.0 * right.rms_error[j]) << "joint " << j + 1 << ": " << right.rms_error[j] << " vs " << bad.rms_error[j];
    }
    // The torque channel 3 ms late: reading it 3 ms later restores the fit.
    const Log late = noise_free_log(model, x, 0.003);
    const HorizonResult ignored = horizons(model, x, late, 0.0), undone = horizons(model, x, late, 0.003);
    for (std::size_t j = 0; j < 2; ++j) {
        EXPECT_LT(undone.rms_error[j], 2.0 * right.rms_error[j] + 1e-6) << "joint " << j + 1;
        EXPECT_GT(ignored.rms_error[j], 5.0 * undone.rms_error[j]) << "joint " << j + 1;
    }
}

// Parameters no rigid body has (ZZ2 < 0: the inertia matrix is not positive definite anywhere) and a model
// whose open-loop motion runs away (ZZ1R 50x too small against the measured torque): the segments are
// reported as diverged, with where and why, excluded from the figures (NaN when none is left), never thrown
// and never averaged into a 1e+110 figure.
TEST(HorizonSimulation, DivergedSegmentsAreReportedAndExcluded) {
    const robot::Planar2RModel model(robot::Planar2RConfig{0.5, {robot::CoulombModel::SmoothAtan, 100.0}, false, false});
    const std::vector<double> table = robot::paper_table2_parameters(model);
    const Eigen::VectorXd x = Eigen::Map<const Eigen::VectorXd>(table.data(), static_cast<Eigen::Index>(table.size()));
    const Log log = noise_free_log(model, x, 0.0);

    Eigen::VectorXd impossible = x;
    impossible[model.parameter_index("ZZ2")] = -0.05;
    const HorizonResult none = horizons(model, impossible, log, 0.0);
    EXPECT_EQ(none.diverged, none.segments);
    ASSERT_FALSE(none.divergences.empty());
    EXPECT_EQ(none.divergences.front().joint, -1);
    EXPECT_NE(none.divergences.front().why.find("not positive definite"), std::string::npos);
    for (std::size_t j = 0; j < 2; ++j) EXPECT_TRUE(std::isnan(none.rms_error[j]));
    EXPECT_NE(none.divergence_summary().find(std::to_string(none.segments) + " of " + std::to_string(none.segments)), std::string::npos);

    Eigen::VectorXd runaway = x;
    runaway[model.parameter_index("ZZ1R")] /= 50.0;
    const HorizonResult some = horizons(model, runaway, log, 0.0);
    EXPECT_GT(some.diverged, 0u);
    ASSERT_FALSE(some.divergences.empty());
    EXPECT_NE(some.divergences.front().why.find("left the measured path"), std::string::npos);
    for (std::size_t j = 0; j < 2; ++j) {
        if (some.diverged < some.segments) EXPECT_LT(some.rms_error[j], 1.0) << "joint " << j + 1;
        else EXPECT_TRUE(std::isnan(some.rms_error[j]));
    }
    // The right model diverges nowhere.
    EXPECT_EQ(horizons(model, x, log, 0.0).diverged, 0u);
}

// Several logs' figures pooled (diagnose --in a --in b): by hand, joint 1's RMS over the kept segments of
// both logs is sqrt((2 x 1^2 + 2 x 3^2) / 4) = sqrt(5); a log whose segments all diverged adds only its count.
TEST(HorizonSimulation, SeveralLogsArePooledOverTheirKeptSegments) {
    HorizonResult a, b, c;
    a.segments = 3, a.diverged = 1, a.rms_error = {1.0, 2.0}, a.end_error = {2.0, 2.0};
    a.divergences = {{1.0, 0.1, 0, "left the measured path by more than 1 rad"}};
    b.segments = 2, b.diverged = 0, b.rms_error = {3.0, 4.0}, b.end_error = {4.0, 0.0};
    const double nan = std::numeric_limits<double>::quiet_NaN();
    c.segments = 1, c.diverged = 1, c.rms_error = {nan, nan}, c.end_error = {nan, nan};
    c.divergences = {{7.0, 0.0, -1, "no finite state"}};
    const HorizonResult p = pooled_horizons({a, b, c});
    EXPECT_EQ(p.segments, 6u);
    EXPECT_EQ(p.diverged, 2u);
    ASSERT_EQ(p.divergences.size(), 2u);
    EXPECT_EQ(p.divergences[1].why, "no finite state");
    EXPECT_DOUBLE_EQ(p.rms_error[0], std::sqrt(5.0));
    EXPECT_DOUBLE_EQ(p.rms_error[1], std::sqrt(10.0));
    EXPECT_DOUBLE_EQ(p.end_error[0], std::sqrt(10.0));
    EXPECT_DOUBLE_EQ(p.end_error[1], std::sqrt(2.0));
    const HorizonResult none = pooled_horizons({c, c});
    EXPECT_TRUE(std::isnan(none.rms_error[0]));
}

// Two logs' decimated rows stacked: each row keeps its own W and, shifted in time, reads its own log's
// filtered torque (the sample offsets), exactly as the rows of each log alone do.
TEST(StackedRows, EachRowReadsItsOwnLogsTorqueWhenShifted) {
    const robot::Planar2RModel model(robot::Planar2RConfig{0.5, {robot::CoulombModel::SmoothAtan, 100.0}, false, false});
    const std::vector<double> table = robot::paper_table2_parameters(model);
    const Eigen::VectorXd x = Eigen::Map<const Eigen::VectorXd>(table.data(), static_cast<Eigen::Index>(table.size()));
    const Log a = noise_free_log(model, x, 0.0), b = noise_free_log(model, x, 0.004);
    const std::vector<identify::LogColumns> logs{a.columns, b.columns};
    const identify::SegmentPlan plan = identify::plan_segments(logs, identify::PipelineSettings{}, {"--in", "log"});
    const DecimatedRows ra = decimated_rows(model, a.columns, plan.fixed), rb = decimated_rows(model, b.columns, plan.fixed);
    const DecimatedRows all = stacked_decimated_rows(model, logs, plan.fixed, plan.info);
    ASSERT_EQ(all.rows(), ra.rows() + rb.rows());
    const auto m = static_cast<Eigen::Index>(ra.rows());
    EXPECT_GT(all.t[ra.rows()], all.t[ra.rows() - 1]) << "the second log's times follow the first's";
    for (const double delay : {0.0, 0.002, -0.003, 0.0005}) {
        for (int j = 0; j < 2; ++j) {
            const Eigen::VectorXd y = all.shifted_y(j, delay), ya = ra.shifted_y(j, delay), yb = rb.shifted_y(j, delay);
            EXPECT_EQ(y.head(m), ya) << "joint " << j + 1 << ", delay " << delay;
            EXPECT_EQ(y.tail(y.size() - m), yb) << "joint " << j + 1 << ", delay " << delay;
            const auto ju = static_cast<std::size_t>(j);
            EXPECT_EQ(all.w[ju].topRows(m), ra.w[ju]);
            EXPECT_EQ(all.w[ju].bottomRows(all.w[ju].rows() - m), rb.w[ju]);
        }
    }
}

TEST(ResidualAnalysis, FindsTheHarmonicAndTheVelocityStep) {
    std::mt19937_64 rng(4);
    std::uniform_real_distribution<double> angle(-2.5, 2.5);
    std::normal_distribution<double> normal;
    const int m = 4000;
    Eigen::MatrixXd state(m, 3);
    Eigen::VectorXd r(m);
    std::vector<double> t;
    for (int i = 0; i < m; ++i) {
        state(i, 0) = angle(rng);
        state(i, 1) = normal(rng);
        state(i, 2) = 10.0 * normal(rng);
        // 0.1 N.m at 7 per revolution, and +0.05 N.m only while moving forward faster than 0.05 rad/s.
        r[i] = 0.1 * std::sin(7.0 * state(i, 0) + 0.3) + (state(i, 1) > 0.05 ? 0.05 : 0.0) + 0.01 * normal(rng);
        t.push_back(1e-2 * i);
    }
    const JointResidualAnalysis a = analyse_residual(r, state, t, 0.05, 30);
    EXPECT_EQ(a.dominant_order, 7);
    EXPECT_NEAR(a.dominant_amplitude, 0.1, 0.01);
    ASSERT_EQ(a.velocity.size(), 5u);
    EXPECT_NEAR(a.velocity[0].mean, 0.0, 0.01);  // fast backwards
    EXPECT_NEAR(a.velocity[2].mean, 0.0, 0.01);  // near zero
    EXPECT_NEAR(a.velocity[4].mean, 0.05, 0.01);  // fast forwards
    EXPECT_NE(a.findings.front().find("qd >"), std::string::npos) << a.findings.front();
}

// A held torque at rest (0.3 N.m while |qd| < 0.05 rad/s and |qdd| < 0.25 rad/s^2), nothing while moving or
// passing through zero velocity: the motion-state split puts all of it, and its energy, at rest.
TEST(ResidualAnalysis, MotionStateSplitLocatesATorqueHeldAtRest) {
    std::mt19937_64 rng(5);
    std::normal_distribution<double> normal;
    const int m = 3000;
    Eigen::MatrixXd state(m, 3);
    Eigen::VectorXd r(m);
    std::vector<double> t;
    int at_rest = 0, reversing = 0;
    for (int i = 0; i < m; ++i) {
        const int phase = i % 3;  // rest, reversal, motion, in turn
        state(i, 0) = 0.1 * normal(rng);
        state(i, 1) = phase == 2 ? 0.5 + 0.1 * std::abs(normal(rng)) : 0.01 * normal(rng);
        state(i, 2) = phase == 1 ? 2.0 + std::abs(normal(rng)) : 0.01 * normal(rng);
        const bool rest = std::abs(state(i, 1)) < 0.05 && std::abs(state(i, 2)) < 0.25;
        at_rest += rest;
        reversing += std::abs(state(i, 1)) < 0.05 && !rest;
        r[i] = (rest ? 0.3 : 0.0) + 0.01 * normal(rng);
        t.push_back(1e-2 * i);
    }
    const JointResidualAnalysis a = analyse_residual(r, state, t, 0.05, 5);
    ASSERT_EQ(a.motion.size(), 3u);
    EXPECT_EQ(a.motion[0].state, "at rest");
    EXPECT_EQ(a.motion[0].count, static_cast<std::size_t>(at_rest));
    EXPECT_EQ(a.motion[1].count, static_cast<std::size_t>(reversing));
    EXPECT_EQ(a.motion[2].count, static_cast<std::size_t>(m - at_rest - reversing));
    EXPECT_NEAR(a.motion[0].mean, 0.3, 0.005);
    EXPECT_NEAR(a.motion[1].mean, 0.0, 0.005);
    EXPECT_NEAR(a.motion[2].mean, 0.0, 0.005);
    EXPECT_GT(a.motion[0].energy_share, 0.99);
    EXPECT_NEAR(a.motion[0].row_share + a.motion[1].row_share + a.motion[2].row_share, 1.0, 1e-12);
    bool found = false;
    for (const auto& f : a.findings) found = found || f.rfind("by motion state: at rest", 0) == 0;
    EXPECT_TRUE(found);
}

}  // namespace
}  // namespace jacobid::diagnose
