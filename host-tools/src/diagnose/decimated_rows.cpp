// SPDX-License-Identifier: MIT
#include "diagnose/decimated_rows.hpp"

#include <algorithm>
#include <cmath>

namespace jacobid::diagnose {
using identify::sample_at;

Eigen::VectorXd DecimatedRows::shifted_y(int joint, double delay) const {
    const auto& tf = tau_filtered[static_cast<std::size_t>(joint)];
    Eigen::VectorXd out(static_cast<Eigen::Index>(rows()));
    const double shift = delay / sample_period;
    for (std::size_t i = 0; i < rows(); ++i) out[static_cast<Eigen::Index>(i)] = sample_at(tf, static_cast<double>(sample[i]) + shift);
    return out;
}

std::vector<Eigen::VectorXd> DecimatedRows::shifted_ys(double delay) const {
    if (delay == 0.0) return y;
    std::vector<Eigen::VectorXd> out;
    for (int j = 0; j < joints(); ++j) out.push_back(shifted_y(j, delay));
    return out;
}

namespace {

// Keeps every row run_pipeline folds into the least squares, with its sample index and state, and the
// full-rate filtered torque the rows' Y are sampled from (for shifted_y).
class RowCollector final : public identify::RowSink {
public:
    RowCollector(DecimatedRows& out, std::size_t joints, std::size_t samples)
        : out_(out), w_(joints), state_(joints), y_(joints) {
        out_.tau_filtered.assign(joints, std::vector<double>(samples, 0.0));
    }
    void row(const identify::DecimatedRow& r) override {
        out_.t.push_back(r.t);
        out_.sample.push_back(r.sample);
        for (std::size_t j = 0; j < y_.size(); ++j) {
            const auto je = static_cast<Eigen::Index>(j);
            for (Eigen::Index p = 0; p < r.w.cols(); ++p) w_[j].push_back(r.w(je, p));
            y_[j].push_back(r.y[je]);
            state_[j].insert(state_[j].end(), {r.q[je], r.qd[je], r.qdd[je]});
        }
    }
    void filtered_torque(std::size_t first, std::size_t count, const std::vector<const double*>& tau) override {
        for (std::size_t j = 0; j < tau.size(); ++j) std::copy(tau[j], tau[j] + count, out_.tau_filtered[j].begin() + static_cast<std::ptrdiff_t>(first));
    }
    // Row-major buffers into the per-joint matrices.
    void finish(Eigen::Index columns) {
        using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
        const auto m = static_cast<Eigen::Index>(out_.t.size());
        for (std::size_t j = 0; j < y_.size(); ++j) {
            out_.w.push_back(Eigen::Map<const RowMajor>(w_[j].data(), m, columns));
            out_.y.push_back(Eigen::Map<const Eigen::VectorXd>(y_[j].data(), m));
            out_.state.push_back(Eigen::Map<const RowMajor>(state_[j].data(), m, 3));
        }
    }

private:
    DecimatedRows& out_;
    std::vector<std::vector<double>> w_, state_, y_;
};

}  // namespace

DecimatedRows decimated_rows(const robot::RobotModel& model, const identify::LogColumns& log, const identify::PipelineSettings& settings) {
    identify::PipelineSettings s = settings;
    s.plot_rows = 0;  // the rows come through the collector
    s.residual_lags = 0;  // the diagnosis computes its own effective sample sizes from the rows
    s.progress = false;
    DecimatedRows r;
    r.names = model.parameter_names();
    r.sample_period = log.sample_period;
    RowCollector collector(r, static_cast<std::size_t>(model.joint_count()), log.samples());
    r.info = identify::run_pipeline(model, log, s, &collector).info;
    collector.finish(model.parameter_count());
    // Outside the valid derivative range [first, last) the filtered torque holds its end values.
    for (auto& tf : r.tau_filtered) {
        const std::size_t a0 = r.info.first, a1 = r.info.last;
        std::fill(tf.begin(), tf.begin() + static_cast<std::ptrdiff_t>(a0), tf[a0]);
        std::fill(tf.begin() + static_cast<std::ptrdiff_t>(a1), tf.end(), tf[a1 - 1]);
    }
    return r;
}

}  // namespace jacobid::diagnose
