// SPDX-License-Identifier: MIT
#include "identify/validation/validation.hpp"

#include <algorithm>
#include <cmath>

#include "identify/pipeline/pipeline.hpp"
#include "identify/friction/presliding_initial_state.hpp"

namespace jacobid::identify {

PipelineSettings validation_settings(const PipelineSettings& identification, const PipelineInfo& info) {
    PipelineSettings v = identification;
    v.method = info.method;
    v.bandwidth = info.bandwidth;
    // plan_pipeline resolves windows for the Jacobi method only (0 otherwise, which the Butterworth path
    // never reads), so copying them whatever the method changes nothing for Butterworth.
    v.velocity_window = info.velocity_window;
    v.acceleration_window = info.acceleration_window;
    v.differentiator_cutoff = info.differentiator_cutoff;
    v.decimation_cutoff = info.decimation_cutoff;
    v.coulomb_velocity_ratios = info.coulomb_velocity_ratios;
    // The raw full-rate comparison differentiates at the motion's own band (differentiator ratio x the velocity's
    // bandwidth, as before the torque rule): widened to the torque's band, the differentiators keep the fit and the
    // filtered comparison unbiased (bandwidth.hpp), but at full rate nothing filters the acceleration noise the
    // wider band lets in, which then dominates the raw error (example 01: 0.19 -> 0.63 N.m, the parameters unchanged).
    // An explicit --cutoff is used as given.
    if (info.bandwidth_estimated && identification.differentiator_cutoff <= 0.0) {
        v.raw_differentiator_cutoff = std::min(identification.differentiator_ratio * info.bandwidth, info.differentiator_cutoff);
    }
    v.progress = false;
    v.kept_from = v.kept_to = 0;  // another log: all of it
    return v;
}

ValidationResult validate_prediction(const robot::RobotModel& fitted, const LogColumns& log, const PipelineSettings& settings,
                                     const Eigen::VectorXd& x_in) {
    PipelineSettings raw = settings;
    if (settings.raw_differentiator_cutoff > 0.0 && settings.raw_differentiator_cutoff != settings.differentiator_cutoff) {
        raw.differentiator_cutoff = settings.raw_differentiator_cutoff;
        raw.velocity_window = raw.acceleration_window = 0.0;  // designed anew for that cutoff
    }
    PipelineInfo info = plan_pipeline(log, raw);
    const StateEstimates e = estimate_states(log, raw, info);
    const Eigen::VectorXd x = x_in.unaryExpr([](double v) { return std::isnan(v) ? 0.0 : v; });
    // Friction with memory starts from the state observed at the log's start (presliding_initial_state.hpp).
    std::unique_ptr<robot::RobotModel> observed;
    const robot::RobotModel& model = with_observed_initial_state(fitted, log, x, observed);
    const int joints = model.joint_count();
    ValidationResult r;
    r.source = log.source;
    const auto nj = static_cast<std::size_t>(joints);
    r.rms_error.assign(nj, 0.0);
    r.raw_rms_error.assign(nj, 0.0);
    r.raw_differentiator_cutoff = info.differentiator_cutoff;
    r.rms_torque.assign(nj, 0.0);
    r.measured.resize(nj);
    r.predicted.resize(nj);
    // Filtered comparison: the identification pipeline on the new log, residual of the given X.
    PipelineSettings quiet = settings;
    quiet.progress = false;
    quiet.residual_lags = 0;  // a residual, no standard deviations
    const PipelineOutput out = run_pipeline(model, log, quiet);
    double e2 = 0.0, y2 = 0.0;
    const Eigen::Index c = model.parameter_count();
    for (std::size_t j = 0; j < nj; ++j) {
        const Eigen::MatrixXd& f = out.factors.r[j];
        Eigen::VectorXd v = f.leftCols(c) * x - f.col(c);
        const double rows = static_cast<double>(out.factors.rows[j]);
        r.rms_error[j] = v.norm() / std::sqrt(rows);
        r.rms_torque[j] = f.col(c).norm() / std::sqrt(rows);
        e2 += v.squaredNorm();
        y2 += f.col(c).squaredNorm();
        for (std::size_t k = 0; k < out.plot.t.size(); ++k) {
            double model_torque = 0.0;
            for (Eigen::Index p = 0; p < c; ++p) model_torque += out.plot.w[j][k * static_cast<std::size_t>(c) + static_cast<std::size_t>(p)] * x[p];
            r.measured[j].push_back(out.plot.y[j][k]);
            r.predicted[j].push_back(model_torque);
        }
    }
    r.t = out.plot.t;
    r.samples = out.factors.rows.empty() ? 0 : out.factors.rows.front();
    r.relative_error = y2 > 0 ? std::sqrt(e2 / y2) : 0.0;

    // Raw full-rate comparison over the valid derivative range.
    Eigen::MatrixXd D(joints, model.parameter_count());
    std::vector<double> q(nj), qd(nj), qdd(nj);
    const auto history_size = static_cast<std::size_t>(model.history_size());
    std::vector<double> history;  // presliding state along the raw positions, as in run_pipeline
    model.integrate_history(log.q, history);
    for (std::size_t k = e.first; k < e.last; ++k) {
        for (std::size_t j = 0; j < nj; ++j) {
            q[j] = e.q[j][k];
            qd[j] = e.qd[j][k];
            qdd[j] = e.qdd[j][k];
        }
        model.regressor(q.data(), qd.data(), qdd.data(), D);
        if (history_size > 0) model.history_columns(history.data() + k * history_size, D);
        const Eigen::VectorXd tau = D * x;
        for (std::size_t j = 0; j < nj; ++j) {
            const double err = (*log.tau[j])[k] - tau[static_cast<Eigen::Index>(j)];
            r.raw_rms_error[j] += err * err;
        }
    }
    r.raw_samples = e.last - e.first;
    for (std::size_t j = 0; j < nj; ++j) r.raw_rms_error[j] = std::sqrt(r.raw_rms_error[j] / static_cast<double>(e.last - e.first));
    return r;
}

}  // namespace jacobid::identify
