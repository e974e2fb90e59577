// SPDX-License-Identifier: MIT
#include "diagnose/decimated_rows.hpp"

#include <fmt/core.h>

#include <cmath>
#include <limits>

#include "core/errors.hpp"
#include "jacobid/baseline/filtfilt.hpp"
#include "signal/baseline_response.hpp"

namespace jacobid::diagnose {
namespace {

// Linear interpolation of x at fractional index `at`, clamped to the record.
double sample_at(const std::vector<double>& x, double at) {
    if (!(at > 0.0)) return x.front();
    const auto i = static_cast<std::size_t>(std::floor(at));
    if (i + 1 >= x.size()) return x.back();
    const double f = at - static_cast<double>(i);
    return (1.0 - f) * x[i] + f * x[i + 1];
}

}  // namespace

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
    s.plot_rows = std::numeric_limits<std::size_t>::max();
    s.progress = false;
    identify::PipelineOutput out = identify::run_pipeline(model, log, s);
    DecimatedRows r;
    r.info = out.info;
    r.names = model.parameter_names();
    r.t = out.plot.t;
    r.sample_period = log.sample_period;
    const int joints = model.joint_count();
    const Eigen::Index c = model.parameter_count();
    const auto m = static_cast<Eigen::Index>(r.t.size());
    for (double t : r.t) r.sample.push_back(static_cast<std::size_t>(std::llround((t - log.start_time) / log.sample_period)));
    identify::PipelineInfo info = out.info;
    const identify::StateEstimates e = identify::estimate_states(log, s, info);
    const signal::ButterworthSos fp =
        signal::design_butterworth_or_throw(s.decimation_order, out.info.decimation_cutoff, log.sample_period, "decimation filter F_p");
    std::vector<double> workspace(sosfiltfilt_workspace_size(fp));
    for (int j = 0; j < joints; ++j) {
        const auto js = static_cast<std::size_t>(j);
        r.w.push_back(Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(out.plot.w[js].data(), m, c));
        r.y.push_back(Eigen::Map<const Eigen::VectorXd>(out.plot.y[js].data(), m));
        Eigen::MatrixXd st(m, 3);
        for (Eigen::Index i = 0; i < m; ++i) {
            const std::size_t k = r.sample[static_cast<std::size_t>(i)];
            st(i, 0) = e.q[js][k];
            st(i, 1) = e.qd[js][k];
            st(i, 2) = e.qdd[js][k];
        }
        r.state.push_back(std::move(st));
        // Whole-record F_p over the valid derivative range, as the pipeline filters it chunk by chunk.
        std::vector<double> tf(log.samples(), 0.0);
        const std::size_t a0 = out.info.first, a1 = out.info.last;
        const FilterStatus status = sosfiltfilt(fp, Span<const double>(log.tau[js]->data() + a0, a1 - a0), Span<double>(tf.data() + a0, a1 - a0),
                                                Span<double>(workspace));
        if (status != FilterStatus::Ok) throw InputError(fmt::format("{}: F_p on the torque: {}", log.source, describe(status)));
        for (std::size_t k = 0; k < a0; ++k) tf[k] = tf[a0];
        for (std::size_t k = a1; k < tf.size(); ++k) tf[k] = tf[a1 - 1];
        r.tau_filtered.push_back(std::move(tf));
    }
    return r;
}

ShiftedTorques shift_torques(const identify::LogColumns& log, double delay) {
    ShiftedTorques s;
    s.log = log;
    const double shift = delay / log.sample_period;
    s.tau.resize(log.tau.size());
    for (std::size_t j = 0; j < log.tau.size(); ++j) {
        const auto& x = *log.tau[j];
        s.tau[j].resize(x.size());
        for (std::size_t k = 0; k < x.size(); ++k) s.tau[j][k] = sample_at(x, static_cast<double>(k) + shift);
    }
    for (std::size_t j = 0; j < log.tau.size(); ++j) s.log.tau[j] = &s.tau[j];
    return s;
}

}  // namespace jacobid::diagnose
