// SPDX-License-Identifier: MIT
#include "diagnose/decimated_rows.hpp"

#include <algorithm>
#include <cmath>

#include "identify/row_collector.hpp"

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

DecimatedRows decimated_rows(const robot::RobotModel& model, const identify::LogColumns& log, const identify::PipelineSettings& settings) {
    identify::PipelineSettings s = settings;
    s.plot_rows = 0;  // the rows come through the collector
    s.residual_lags = 0;  // the diagnosis computes its own effective sample sizes from the rows
    s.progress = false;
    DecimatedRows r;
    r.names = model.parameter_names();
    r.sample_period = log.sample_period;
    const auto joints = static_cast<std::size_t>(model.joint_count());
    identify::RowCollectorSettings keep;
    keep.torque_and_states = true;
    identify::RowCollector collector(joints, log.samples(), keep);
    r.info = identify::run_pipeline(model, log, s, &collector).info;
    // Row-major buffers into the per-joint matrices.
    using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
    const auto m = static_cast<Eigen::Index>(collector.rows());
    r.t = collector.times();
    r.sample = collector.samples();
    for (std::size_t j = 0; j < joints; ++j) {
        r.w.push_back(Eigen::Map<const RowMajor>(collector.w(j).data(), m, model.parameter_count()));
        r.y.push_back(Eigen::Map<const Eigen::VectorXd>(collector.y(j).data(), m));
        r.state.push_back(Eigen::Map<const RowMajor>(collector.states(j).data(), m, 3));
    }
    r.tau_filtered = std::move(collector.filtered_torque());
    // Outside the valid derivative range [first, last) the filtered torque holds its end values.
    for (auto& tf : r.tau_filtered) {
        const std::size_t a0 = r.info.first, a1 = r.info.last;
        std::fill(tf.begin(), tf.begin() + static_cast<std::ptrdiff_t>(a0), tf[a0]);
        std::fill(tf.begin() + static_cast<std::ptrdiff_t>(a1), tf.end(), tf[a1 - 1]);
    }
    return r;
}

}  // namespace jacobid::diagnose
