// SPDX-License-Identifier: MIT
#include "identify/physical/physical_identification.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/errors.hpp"
#include "identify/physical/plausibility.hpp"
#include "robot/presliding_model.hpp"
#include "robot/serial_robot_model.hpp"

namespace jacobid::identify {
namespace {

// ||R_j [x; -1]|| of joint j's factor: its residual norm at x (unweighted).
double joint_residual_norm(const Eigen::MatrixXd& r, const Eigen::VectorXd& x) {
    Eigen::VectorXd v(x.size() + 1);
    v << x, -1.0;
    return (r * v).norm();
}

double cost_increase_percent(const PhysicalFit& f) {
    return f.unconstrained_data_cost > 0.0 ? 100.0 * (f.data_cost - f.unconstrained_data_cost) / f.unconstrained_data_cost : 0.0;
}

}  // namespace

void make_physically_consistent(IdentifiedLog& fit, const robot::RobotDescription& description, const robot::RobotModel& nominal,
                                PhysicalSettings settings) {
    const robot::RobotModel& fitted = fit.smoothed.get(nominal);
    // The rigid body's standard parameters, followed by the columns a wrapper appends (Dahl presliding FDj),
    // which are their own standard parameters (identity regrouping).
    const auto* serial = dynamic_cast<const robot::SerialRobotModel*>(&robot::rigid_body(fitted));
    if (!serial) {
        throw InputError(fmt::format("--{}: model {} has no standard (per-link) parameters; describe the robot with model mdh or urdf",
                                     to_string(settings.constraint), fitted.model_name()));
    }
    const Eigen::Index base_count = serial->parameter_count(), appended = fitted.parameter_count() - base_count;
    const Eigen::Index standard_count = serial->standard_parameter_count();
    std::vector<std::string> standard_names = serial->standard_names();
    for (Eigen::Index k = 0; k < appended; ++k) standard_names.push_back(fitted.parameter_names()[static_cast<std::size_t>(base_count + k)]);
    Eigen::MatrixXd regrouping = Eigen::MatrixXd::Zero(base_count + appended, standard_count + appended);
    regrouping.topLeftCorner(base_count, standard_count) = serial->base().regrouping;
    regrouping.bottomRightCorner(appended, appended).setIdentity();

    LsSolution& s = fit.result.solution;
    const std::size_t joints = fit.factors.r.size();
    std::vector<double> scale = s.joint_weights;
    if (scale.size() != joints) scale.assign(joints, 1.0);
    const Eigen::MatrixXd factor = stacked_factor(fit.factors, scale);
    // The residual variance of the problem solved: the weighted rows have about unit variance.
    const double sigma2 = std::isfinite(s.sigma_rho) && s.sigma_rho > 0.0 ? s.sigma_rho * s.sigma_rho : 1.0;
    // The prior: the standard values the description gives (URDF inertials, `parameters`); the others (friction,
    // rotor inertias a URDF does not have) are left to the data.
    // A presliding level given in `parameters` (FDj) is the prior of its appended column.
    settings.prior = Eigen::VectorXd::Constant(standard_count + appended, std::numeric_limits<double>::quiet_NaN());
    for (const auto* list : {&description.model_parameters, &description.parameters}) {
        for (const auto& [name, value] : *list) {
            const auto named = std::find(standard_names.begin(), standard_names.end(), name);
            if (named != standard_names.end()) settings.prior[named - standard_names.begin()] = value;
        }
    }

    PhysicalReport report;
    report.prior_weight = settings.prior_weight;
    report.standard_names = standard_names;
    report.unconstrained_x = s.x;
    for (Eigen::Index b = 0; b < s.x.size(); ++b) {
        if (!std::isfinite(s.x[b])) report.not_identified.push_back(fitted.parameter_names()[static_cast<std::size_t>(b)]);
    }
    const auto start = std::chrono::steady_clock::now();
    try {
        report.fit = solve_physical(factor, sigma2, regrouping, standard_names, s.x, settings);
    } catch (const std::invalid_argument& e) {
        throw InputError(fmt::format("--{}: {}", to_string(settings.constraint), e.what()));
    }
    report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    // The consistent values everywhere the solution's values are read; norms recomputed at them.
    s.x = report.fit.base;
    // The reported norms are the unweighted ones, as least_squares reports them.
    double e2 = 0.0;
    for (std::size_t j = 0; j < joints; ++j) {
        const double e = joint_residual_norm(fit.factors.r[j], s.x);
        if (j < s.joint_residual_rms.size() && fit.factors.rows[j] > 0) s.joint_residual_rms[j] = e / std::sqrt(static_cast<double>(fit.factors.rows[j]));
        e2 += e * e;
    }
    s.residual_norm = std::sqrt(e2);
    s.relative_error_norm = s.y_norm > 0.0 ? s.residual_norm / s.y_norm : s.relative_error_norm;
    for (Eigen::Index i = 0; i < s.rel_std_percent.size(); ++i) {
        if (std::isfinite(s.std_dev[i]) && s.x[i] != 0.0) s.rel_std_percent[i] = 100.0 * s.std_dev[i] / std::abs(s.x[i]);
    }
    fit.result.violations = plausibility_violations(sign_constraints(fitted), s);
    fit.result.physical = std::move(report);
}

std::string describe(const PhysicalReport& r) {
    const PhysicalFit& f = r.fit;
    std::string active;
    for (const auto& a : f.active) active += (active.empty() ? "" : "; ") + a;
    std::string prior_only;
    for (const auto& name : r.not_identified) prior_only += (prior_only.empty() ? "" : ", ") + name;
    return fmt::format("{}: chi^2 {:.6g} vs {:.6g} unconstrained ({:+.3g} %), prior weight {:.3g}, {} Newton steps in {:.2f} s, duality gap {:.2g}{}; "
                       "active constraints: {}{}",
                       to_string(f.constraint), f.data_cost, f.unconstrained_data_cost, cost_increase_percent(f), r.prior_weight, f.iterations,
                       r.seconds, f.duality_gap, f.converged ? "" : " (NOT converged)", active.empty() ? "none" : active,
                       prior_only.empty() ? "" : "; not identified by the log, values from the prior: " + prior_only);
}

nlohmann::json physical_json(const PhysicalReport& r) {
    const PhysicalFit& f = r.fit;
    nlohmann::json standard = nlohmann::json::object(), projected = nlohmann::json::object();
    for (std::size_t i = 0; i < r.standard_names.size(); ++i) {
        standard[r.standard_names[i]] = f.standard[static_cast<Eigen::Index>(i)];
        projected[r.standard_names[i]] = f.projected_standard[static_cast<Eigen::Index>(i)];
    }
    return {{"constraint", to_string(f.constraint)},
            {"prior_weight", r.prior_weight},
            {"iterations", f.iterations},
            {"converged", f.converged},
            {"duality_gap", f.duality_gap},
            {"seconds", r.seconds},
            {"data_cost", f.data_cost},
            {"unconstrained_data_cost", f.unconstrained_data_cost},
            {"cost_increase_percent", cost_increase_percent(f)},
            {"prior_cost", f.prior_cost},
            {"active", f.active},
            {"not_identified", r.not_identified},
            {"standard", standard},
            {"projected_standard", projected}};
}

}  // namespace jacobid::identify
