// SPDX-License-Identifier: MIT
// identify::RowSink: the rows run_pipeline hands out are the rows of its least squares, at their own sample
// indices, and the filtered torque pieces tile the valid range and equal one whole-record F_p.
#include <gtest/gtest.h>

#include <cmath>

#include "core/errors.hpp"
#include "identify/plan/log_columns.hpp"
#include "identify/pipeline/pipeline.hpp"
#include "identify/pipeline/torque_smoothing.hpp"
#include "identify/validation/validation.hpp"
#include "jacobid/baseline/filtfilt.hpp"
#include "jacobid/kernel_design.hpp"
#include "robot/robot_description.hpp"
#include "signal/baseline_response.hpp"

namespace jacobid::identify {
namespace {

constexpr double kTs = 1e-3, kPi = 3.14159265358979323846;

// Two joints on sines (known derivatives), torques that are any smooth signal: the rows' bookkeeping does
// not need a consistent model.
struct SineLog {
    std::vector<std::vector<double>> q{2}, tau{2};
    LogColumns log;
    explicit SineLog(std::size_t n, double start = 2.5) {
        for (std::size_t k = 0; k < n; ++k) {
            const double t = start + static_cast<double>(k) * kTs;
            q[0].push_back(0.8 * std::sin(2 * kPi * 0.4 * t));
            q[1].push_back(0.5 * std::sin(2 * kPi * 0.7 * t + 1.0));
            tau[0].push_back(3.0 * std::cos(2 * kPi * 0.3 * t) + 0.4 * std::sin(2 * kPi * 9.0 * t));
            tau[1].push_back(0.7 * std::sin(2 * kPi * 1.3 * t));
        }
        log = log_columns(q, tau, kTs, "sines", start);
    }
};

struct Collected : RowSink {
    std::vector<DecimatedRow> rows;
    std::vector<std::pair<std::size_t, std::size_t>> pieces;  // first, count
    std::vector<std::vector<double>> torque{2};
    void row(const DecimatedRow& r) override { rows.push_back(r); }
    void filtered_torque(std::size_t first, std::size_t count, const std::vector<const double*>& tau) override {
        pieces.emplace_back(first, count);
        for (std::size_t j = 0; j < tau.size(); ++j) torque[j].insert(torque[j].end(), tau[j], tau[j] + count);
    }
};

PipelineSettings settings_for_test() {
    PipelineSettings s;
    s.bandwidth = 1.0;  // fixed: the test does not depend on the bandwidth estimate
    s.chunk = 1000;     // several F_p chunks (raised to 4 margins by the pipeline)
    return s;
}

TEST(PipelineRows, AreTheRowsOfTheLeastSquares) {
    const SineLog data(60'000);
    const auto model = robot::make_robot_model(robot::default_planar2r_description());
    Collected sink;
    const PipelineOutput out = run_pipeline(*model, data.log, settings_for_test(), &sink);
    const PipelineInfo& info = out.info;
    ASSERT_EQ(sink.rows.size(), out.factors.rows[0]);
    ASSERT_EQ(sink.rows.size(), out.factors.rows[1]);
    // Gram of [W_j Y_j] from the handed-out rows equals R_j^T R_j of the pipeline's QR factors.
    const Eigen::Index c = model->parameter_count();
    for (Eigen::Index j = 0; j < 2; ++j) {
        Eigen::MatrixXd gram = Eigen::MatrixXd::Zero(c + 1, c + 1);
        for (const auto& r : sink.rows) {
            Eigen::VectorXd a(c + 1);
            a << r.w.row(j).transpose(), r.y[j];
            gram += a * a.transpose();
        }
        const Eigen::MatrixXd& R = out.factors.r[static_cast<std::size_t>(j)];
        EXPECT_LT((gram - R.transpose() * R).norm(), 1e-10 * gram.norm()) << "joint " << j;
    }
    // Sample indices: every d-th sample of the valid range, inside F_p's cropped ends; t from the index.
    for (std::size_t i = 0; i < sink.rows.size(); ++i) {
        const DecimatedRow& r = sink.rows[i];
        EXPECT_GE(r.sample, info.first + info.crop);
        EXPECT_LT(r.sample, info.last - info.crop);
        EXPECT_EQ((r.sample - info.first) % static_cast<std::size_t>(info.decimation), 0u);
        if (i) {
            EXPECT_EQ(r.sample - sink.rows[i - 1].sample, static_cast<std::size_t>(info.decimation));
        }
        EXPECT_DOUBLE_EQ(r.t, 2.5 + static_cast<double>(r.sample) * kTs);
        // Jacobi: q is the measured position; qd and qdd the sines' derivatives at that sample.
        const double t = r.t, w0 = 2 * kPi * 0.4, w1 = 2 * kPi * 0.7;
        EXPECT_EQ(r.q[0], data.q[0][r.sample]);
        EXPECT_NEAR(r.qd[0], 0.8 * w0 * std::cos(w0 * t), 1e-3);
        EXPECT_NEAR(r.qdd[1], -0.5 * w1 * w1 * std::sin(w1 * t + 1.0), 1e-2);
    }
    // The filtered torque: pieces in order, tiling [first, last) once; Y of each row is its sample.
    std::size_t next = info.first;
    for (const auto& [first, count] : sink.pieces) {
        EXPECT_EQ(first, next);
        next = first + count;
    }
    EXPECT_EQ(next, info.last);
    EXPECT_GT(sink.pieces.size(), 2u);
    for (const auto& r : sink.rows) {
        for (Eigen::Index j = 0; j < 2; ++j) EXPECT_EQ(r.y[j], sink.torque[static_cast<std::size_t>(j)][r.sample - info.first]);
    }
    // ... and equals one zero-phase F_p over the whole valid range (the core's sosfiltfilt), chunking or not,
    // of the torque through the velocity kernel's low-pass (torque_smoothing.hpp, the Jacobi method).
    const auto fp = signal::design_butterworth_or_throw(4, info.decimation_cutoff, kTs, "F_p");
    KernelParams pv;
    pv.order = 1;
    pv.sample_period = kTs;
    pv.window = info.velocity_window;
    pv.discretization = Discretization::Exact;
    std::vector<double> wv(tap_count(pv));
    ASSERT_EQ(design_kernel(pv, Span<double>(wv)), KernelStatus::Ok);
    const std::vector<double> smoothing = torque_smoothing_kernel(wv, kTs);
    const std::size_t half = (smoothing.size() - 1) / 2;
    ASSERT_LE(half, info.first);
    std::vector<double> whole(info.last - info.first), smoothed(whole.size()), workspace(sosfiltfilt_workspace_size(fp));
    for (std::size_t j = 0; j < 2; ++j) {
        for (std::size_t k = 0; k < smoothed.size(); ++k) {
            double acc = 0.0;
            for (std::size_t i = 0; i < smoothing.size(); ++i) acc += smoothing[i] * data.tau[j][info.first + k - half + i];
            smoothed[k] = acc;
        }
        ASSERT_EQ(sosfiltfilt(fp, Span<const double>(smoothed), Span<double>(whole), Span<double>(workspace)), FilterStatus::Ok);
        double worst = 0.0;
        for (std::size_t k = 0; k < whole.size(); ++k) worst = std::max(worst, std::abs(whole[k] - sink.torque[j][k]));
        EXPECT_LT(worst, 1e-12) << "joint " << j;
    }
}

// Joint 2 stands exactly still (q2 = 0) for the first 20 s, then starts smoothly: its friction columns FV2
// and FC2 (and their Coulomb filter's raw values) are zero in the first chunks and hold values later.
// Chunked or in one piece, the factors agree: a chunk that lost the columns would change R_2 by the whole
// FV2 / FC2 part.
TEST(PipelineRows, AColumnThatFirstHoldsAValueLateInTheLogIsKept) {
    const std::size_t n = 60'000, still = 20'000;
    std::vector<std::vector<double>> q(2), tau(2);
    for (std::size_t k = 0; k < n; ++k) {
        const double t = static_cast<double>(k) * kTs, t0 = static_cast<double>(still) * kTs;
        q[0].push_back(0.8 * std::sin(2 * kPi * 0.4 * t));
        q[1].push_back(k < still ? 0.0 : 0.4 * (1.0 - std::cos(2 * kPi * 0.7 * (t - t0))));
        tau[0].push_back(3.0 * std::cos(2 * kPi * 0.3 * t));
        tau[1].push_back(0.7 * std::sin(2 * kPi * 1.3 * t));
    }
    const LogColumns log = log_columns(q, tau, kTs, "late start");
    const auto model = robot::make_robot_model(robot::default_planar2r_description());
    PipelineSettings chunked = settings_for_test();
    PipelineSettings whole = chunked;
    whole.chunk = n;
    const PipelineOutput a = run_pipeline(*model, log, chunked, nullptr);
    const PipelineOutput b = run_pipeline(*model, log, whole, nullptr);
    const int fv2 = model->parameter_index("FV2");
    ASSERT_GE(fv2, 0);
    for (std::size_t j = 0; j < 2; ++j) {
        const Eigen::MatrixXd ga = a.factors.r[j].transpose() * a.factors.r[j];
        const Eigen::MatrixXd gb = b.factors.r[j].transpose() * b.factors.r[j];
        EXPECT_LT((ga - gb).norm(), 1e-9 * gb.norm()) << "joint " << j + 1;
    }
    // The columns did hold something: joint 2's FV2 column has energy in its rows.
    const Eigen::MatrixXd g2 = a.factors.r[1].transpose() * a.factors.r[1];
    EXPECT_GT(g2(fv2, fv2), 1.0);
}

// Two unit inertias and a joint-limit spring on joint 2 that engages beyond 10 rad: its column is zero at
// every ordinary state (the fold's first guess of the columns that hold values) and in the first half of the
// log, where joint 2 has not reached the stop.
class LimitSpringModel final : public robot::RobotModel {
public:
    std::string model_name() const override { return "limit spring"; }
    int joint_count() const override { return 2; }
    int parameter_count() const override { return 3; }
    const std::vector<std::string>& parameter_names() const override { return names_; }
    void regressor(const double* q, const double* qd, const double* qdd, Eigen::Ref<Eigen::MatrixXd> D) const override {
        (void)qd;
        D.setZero();
        D(0, 0) = qdd[0];
        D(1, 1) = qdd[1];
        D(1, 2) = q[1] > 10.0 ? q[1] - 10.0 : 0.0;
    }

private:
    std::vector<std::string> names_{"I1", "I2", "K2"};
};

TEST(PipelineRows, AColumnFirstNonzeroInALaterChunkIsWrittenThere) {
    const std::size_t n = 60'000;
    std::vector<std::vector<double>> q(2), tau(2);
    for (std::size_t k = 0; k < n; ++k) {
        const double t = static_cast<double>(k) * kTs;
        q[0].push_back(0.8 * std::sin(2 * kPi * 0.4 * t));
        q[1].push_back(6.0 + 6.0 * t / 60.0 + 0.3 * std::sin(2 * kPi * 0.7 * t));  // past 10 rad after ~40 s
        tau[0].push_back(3.0 * std::cos(2 * kPi * 0.3 * t));
        tau[1].push_back(0.7 * std::sin(2 * kPi * 1.3 * t) + std::max(0.0, q[1].back() - 10.0));
    }
    const LogColumns log = log_columns(q, tau, kTs, "limit spring");
    const LimitSpringModel model;
    PipelineSettings chunked = settings_for_test();
    PipelineSettings whole = chunked;
    whole.chunk = n;
    const PipelineOutput a = run_pipeline(model, log, chunked, nullptr);
    const PipelineOutput b = run_pipeline(model, log, whole, nullptr);
    const Eigen::MatrixXd ga = a.factors.r[1].transpose() * a.factors.r[1];
    const Eigen::MatrixXd gb = b.factors.r[1].transpose() * b.factors.r[1];
    EXPECT_GT(gb(2, 2), 1.0);  // the spring's column holds values
    EXPECT_LT((ga - gb).norm(), 1e-9 * gb.norm());
    // Its squared sum from the spring's own values at the decimated samples (F_p leaves a slow ramp as it is).
    const std::size_t d = static_cast<std::size_t>(a.info.decimation);
    double sum = 0.0;
    for (std::size_t k = a.info.first + a.info.crop; k < a.info.last - a.info.crop; ++k) {
        if ((k - a.info.first) % d == 0) sum += std::pow(std::max(0.0, q[1][k] - 10.0), 2);
    }
    EXPECT_NEAR(ga(2, 2), sum, 0.01 * sum);
}

TEST(PipelineRows, SinkDoesNotChangeTheFactors) {
    const SineLog data(20'000);
    const auto model = robot::make_robot_model(robot::default_planar2r_description());
    Collected sink;
    const PipelineOutput with = run_pipeline(*model, data.log, settings_for_test(), &sink);
    const PipelineOutput without = run_pipeline(*model, data.log, settings_for_test());
    for (std::size_t j = 0; j < 2; ++j) EXPECT_EQ(with.factors.r[j], without.factors.r[j]);
}

TEST(ValidationSettings, PutTheSecondLogThroughTheSameFilters) {
    // A second log with another motion bandwidth: its own plan would choose other windows and F_p.
    const SineLog first(30'000), second(30'000);
    std::vector<std::vector<double>> fast_q{2}, tau{second.tau};
    for (std::size_t k = 0; k < second.q[0].size(); ++k) {
        fast_q[0].push_back(0.3 * std::sin(2 * kPi * 3.0 * static_cast<double>(k) * kTs));
        fast_q[1].push_back(0.3 * std::sin(2 * kPi * 2.0 * static_cast<double>(k) * kTs));
    }
    const LogColumns fast = log_columns(fast_q, tau, kTs, "fast");
    PipelineSettings s;  // bandwidth estimated from each log
    const PipelineInfo identification = plan_pipeline(first.log, s);
    const PipelineInfo own = plan_pipeline(fast, s);
    ASSERT_GT(own.decimation_cutoff, 1.5 * identification.decimation_cutoff);
    const PipelineSettings v = validation_settings(s, identification);
    EXPECT_FALSE(v.progress);
    const PipelineInfo validated = plan_pipeline(fast, v);
    EXPECT_EQ(validated.velocity_window, identification.velocity_window);
    EXPECT_EQ(validated.acceleration_window, identification.acceleration_window);
    EXPECT_EQ(validated.decimation_cutoff, identification.decimation_cutoff);
    EXPECT_EQ(validated.decimation, identification.decimation);
    EXPECT_EQ(validated.first, identification.first);
}

TEST(LogColumnsFromMemory, RejectsMismatchedColumns) {
    const std::vector<std::vector<double>> q{{0, 1, 2}, {0, 1, 2}}, tau{{0, 1, 2}, {0, 1}}, one{{0, 1, 2}};
    EXPECT_THROW(log_columns(q, tau, kTs, "m"), InputError);
    EXPECT_THROW(log_columns(q, one, kTs, "m"), InputError);
    EXPECT_THROW(log_columns(q, q, 0.0, "m"), InputError);
    const LogColumns ok = log_columns(q, q, kTs, "m");
    EXPECT_EQ(ok.samples(), 3u);
    EXPECT_EQ(ok.tau_names[1], "tau2");
}

}  // namespace
}  // namespace jacobid::identify
