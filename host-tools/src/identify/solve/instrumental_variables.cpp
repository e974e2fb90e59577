// SPDX-License-Identifier: MIT
#include "identify/solve/instrumental_variables.hpp"

#include <Eigen/Dense>
#include <fmt/core.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/errors.hpp"
#include "identify/pipeline/row_collector.hpp"

namespace jacobid::identify {
namespace {

LsSolution iv_solution(const RowCollector& measured, const RowCollector& instruments, const LsSolution& current) {
    if (measured.samples() != instruments.samples()) throw std::logic_error("IDIM-IV: measured and simulated rows of different samples");
    // Identified columns only (the start dropped the others, and simulable_parameters required none).
    std::vector<Eigen::Index> active;
    for (std::size_t c = 0; c < current.identified.size(); ++c) {
        if (current.identified[c]) active.push_back(static_cast<Eigen::Index>(c));
    }
    const auto p = static_cast<Eigen::Index>(active.size());
    const auto joints = static_cast<Eigen::Index>(measured.joints());
    const std::size_t columns = measured.parameters();  // per row of W
    Eigen::VectorXd s2 = Eigen::VectorXd::Ones(joints);  // squared joint weights
    for (Eigen::Index j = 0; j < joints && static_cast<std::size_t>(j) < current.joint_weights.size(); ++j) {
        s2[j] = current.joint_weights[static_cast<std::size_t>(j)] * current.joint_weights[static_cast<std::size_t>(j)];
    }
    Eigen::MatrixXd ZW = Eigen::MatrixXd::Zero(p, p), ZZ = Eigen::MatrixXd::Zero(p, p);
    Eigen::VectorXd Zy = Eigen::VectorXd::Zero(p);
    Eigen::VectorXd w(p), z(p);
    for (std::size_t r = 0; r < measured.rows(); ++r) {
        for (Eigen::Index j = 0; j < joints; ++j) {
            const double* measured_row = measured.w(static_cast<std::size_t>(j)).data() + r * columns;
            const double* instrument_row = instruments.w(static_cast<std::size_t>(j)).data() + r * columns;
            for (Eigen::Index a = 0; a < p; ++a) {
                w[a] = measured_row[active[static_cast<std::size_t>(a)]];
                z[a] = instrument_row[active[static_cast<std::size_t>(a)]];
            }
            ZW.noalias() += s2[j] * z * w.transpose();
            ZZ.noalias() += s2[j] * z * z.transpose();
            Zy.noalias() += s2[j] * measured.y(static_cast<std::size_t>(j))[r] * z;
        }
    }
    const Eigen::FullPivLU<Eigen::MatrixXd> lu(ZW);
    if (lu.rank() < p) throw InputError("--estimator iv: the instruments do not excite every identified parameter (Z' W is singular)");
    const Eigen::VectorXd x = lu.solve(Zy);

    LsSolution s = current;
    s.x.setConstant(std::numeric_limits<double>::quiet_NaN());
    for (Eigen::Index a = 0; a < p; ++a) s.x[active[static_cast<std::size_t>(a)]] = x[a];
    // Residuals of the measured rows at X_iv: sigma from the weighted rows (the problem solved), the norms
    // reported unweighted, as least_squares reports them (comparable between estimators).
    double weighted = 0.0, e2 = 0.0, y2 = 0.0;
    std::vector<double> joint_sq(static_cast<std::size_t>(joints), 0.0);
    for (std::size_t r = 0; r < measured.rows(); ++r) {
        for (Eigen::Index j = 0; j < joints; ++j) {
            const double* measured_row = measured.w(static_cast<std::size_t>(j)).data() + r * columns;
            const double y = measured.y(static_cast<std::size_t>(j))[r];
            double fit = 0.0;
            for (Eigen::Index a = 0; a < p; ++a) fit += measured_row[active[static_cast<std::size_t>(a)]] * x[a];
            const double e = y - fit;
            weighted += s2[j] * e * e;
            e2 += e * e;
            y2 += y * y;
            joint_sq[static_cast<std::size_t>(j)] += e * e;
        }
    }
    const auto equations = static_cast<double>(measured.rows() * static_cast<std::size_t>(joints));
    const double sigma2 = weighted / std::max(1.0, equations - static_cast<double>(p));
    const Eigen::MatrixXd inverse = lu.inverse();
    const Eigen::MatrixXd cov = sigma2 * inverse * ZZ * inverse.transpose();
    s.std_dev.setConstant(std::numeric_limits<double>::quiet_NaN());
    s.rel_std_percent.setConstant(std::numeric_limits<double>::quiet_NaN());
    for (Eigen::Index a = 0; a < p; ++a) {
        const Eigen::Index c = active[static_cast<std::size_t>(a)];
        s.std_dev[c] = std::sqrt(std::max(0.0, cov(a, a)));
        s.rel_std_percent[c] = 100.0 * s.std_dev[c] / std::abs(x[a]);
    }
    s.residual_norm = std::sqrt(e2);
    s.y_norm = std::sqrt(y2);
    s.relative_error_norm = s.y_norm > 0.0 ? s.residual_norm / s.y_norm : 0.0;
    s.sigma_rho = std::sqrt(sigma2);
    for (std::size_t j = 0; j < joint_sq.size(); ++j) {
        s.joint_residual_rms[j] = std::sqrt(joint_sq[j] / std::max<double>(1.0, static_cast<double>(measured.rows())));
    }
    // The sandwich above, not the least-squares formulas the start's std method names.
    s.std_method = StdMethod::Pooled;
    s.std_lags = 0;
    s.joint_sigma.clear();
    s.joint_long_run_factors.clear();
    s.joint_lag1_correlation.clear();
    return s;
}

}  // namespace

EstimatorRun identify_iv(const ReferenceSimulation& simulation, const EstimatorSettings& settings, const LsSolution& start, LsSolution& solution) {
    const LogColumns& log = simulation.log;
    PipelineInfo info = simulation.info;
    StateEstimates estimates = estimate_states(log, simulation.pipeline, info);
    // The Coulomb columns s(alpha qd) of a noisy velocity are not the true columns plus zero-mean noise (their
    // expectation is a flatter sign), which no instrument undoes: the measured rows take them from the
    // simulated velocity, through the torque's filter like the torque (StateEstimates::qd_coulomb), so they
    // are exogenous and identical in both matrices (docs/method.md, "Estimators"). With the Coulomb
    // columns off (--coulomb-velocity-ratio 0) the measured velocity stays, as before.
    const bool simulated_coulomb = !estimates.qd_coulomb.empty();
    // The rows of one pass, in order (IV pairs the measured and simulated rows of one sample), with Y.
    RowCollectorSettings keep;
    keep.torque_and_states = true;
    keep.filtered_torque = false;
    const auto new_collector = [&] { return RowCollector(log.q.size(), log.samples(), keep); };
    RowCollector fixed_measured = new_collector();  // without simulated Coulomb columns the measured rows do not change: folded once
    if (!simulated_coulomb) fold_states(simulation.model, log, simulation.pipeline, info, estimates, &fixed_measured);
    return iterate_estimator(settings, start, [&](const LsSolution& current) {
        const StateEstimates simulated = simulation.states(simulable_parameters(current, Estimator::Iv));
        RowCollector measured = new_collector(), instruments = new_collector();
        if (simulated_coulomb) {
            estimates.qd_coulomb = simulated.qd;
            fold_states(simulation.model, log, simulation.pipeline, info, estimates, &measured);
        }
        fold_states(simulation.model, log, simulation.pipeline, simulation.info, simulated, &instruments);
        return iv_solution(simulated_coulomb ? measured : fixed_measured, instruments, current);
    }, solution);
}

}  // namespace jacobid::identify
