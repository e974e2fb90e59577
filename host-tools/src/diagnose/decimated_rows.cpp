// SPDX-License-Identifier: MIT
#include "diagnose/decimated_rows.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/core.h>

#include "core/errors.hpp"
#include "identify/pipeline/row_collector.hpp"

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

DecimatedRows stacked_decimated_rows(const robot::RobotModel& model, const std::vector<identify::LogColumns>& logs,
                                     const identify::PipelineSettings& settings, const identify::PipelineInfo& plan) {
    DecimatedRows all;
    all.names = model.parameter_names();
    all.info = plan;
    all.info.samples = 0;
    std::size_t offset = 0;  // full-rate samples of the logs before this one
    double clock = 0.0;      // campaign time at which this log starts
    identify::PipelineSettings each = settings;
    each.require_own_equations = false;  // a short log adds its rows to the others': the sum is checked below
    for (std::size_t l = 0; l < logs.size(); ++l) {
        DecimatedRows one = decimated_rows(model, logs[l], each);
        if (l == 0) {
            all.sample_period = one.sample_period;
            all.tau_filtered.resize(one.tau_filtered.size());
            all.w.resize(one.w.size());
            all.y.resize(one.y.size());
            all.state.resize(one.state.size());
            clock = logs[l].start_time;
        }
        all.info.samples += one.info.samples;
        const double shift = clock - logs[l].start_time;
        for (std::size_t i = 0; i < one.rows(); ++i) {
            all.t.push_back(one.t[i] + shift);
            all.sample.push_back(one.sample[i] + offset);
        }
        for (std::size_t j = 0; j < one.tau_filtered.size(); ++j) {
            auto& tf = all.tau_filtered[j];
            tf.insert(tf.end(), one.tau_filtered[j].begin(), one.tau_filtered[j].end());
            const auto append = [](auto& to, const auto& from) {
                to.conservativeResize(to.rows() + from.rows(), from.cols());
                to.bottomRows(from.rows()) = from;
            };
            append(all.w[j], one.w[j]);
            append(all.y[j], one.y[j]);
            append(all.state[j], one.state[j]);
        }
        offset += logs[l].samples();
        clock += static_cast<double>(logs[l].samples()) * logs[l].sample_period;
    }
    const std::size_t equations = all.rows() * all.y.size();
    if (equations <= all.names.size()) {
        throw InputError(fmt::format("--in: only {} equations after decimation in the {} logs for {} columns (the model's parameters and the "
                                     "candidate effects): the logs are too short",
                                     equations, logs.size(), all.names.size()));
    }
    return all;
}

}  // namespace jacobid::diagnose
