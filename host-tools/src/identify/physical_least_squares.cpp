// SPDX-License-Identifier: MIT
#include "identify/physical_least_squares.hpp"

#include <fmt/core.h>

#include <Eigen/Cholesky>
#include <Eigen/QR>
#include <cctype>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace jacobid::identify {
namespace {

// The weighted residual vector of the cost as a function of the variables.
class Cost {
public:
    Cost(const Eigen::MatrixXd& factor, double sigma2, const Eigen::MatrixXd& regrouping, const PhysicalParametrization& map,
         const Eigen::VectorXd& prior, const Eigen::VectorXd& prior_scale)
        : map_(map), prior_(prior), prior_scale_(prior_scale) {
        const Eigen::Index c = regrouping.rows();
        const double inv_sigma = 1.0 / std::sqrt(sigma2);
        A_ = inv_sigma * factor.topLeftCorner(c + 1, c) * regrouping;  // (c+1) x standard
        z_ = inv_sigma * factor.col(c);
    }
    Eigen::Index size() const { return A_.rows() + prior_.size(); }
    Eigen::VectorXd residual_of_standard(const Eigen::VectorXd& s) const {
        Eigen::VectorXd r(size());
        r.head(A_.rows()) = A_ * s - z_;
        r.tail(prior_.size()) = (s - prior_).cwiseProduct(prior_scale_);
        return r;
    }
    Eigen::VectorXd residual(const Eigen::VectorXd& v) const { return residual_of_standard(map_.standard(v)); }
    double data_cost(const Eigen::VectorXd& s) const { return (A_ * s - z_).squaredNorm(); }
    double prior_cost(const Eigen::VectorXd& s) const { return (s - prior_).cwiseProduct(prior_scale_).squaredNorm(); }
    // d residual / d v: the standard parameters' Jacobian by central differences (the map is a few
    // exponentials and 4x4 products per link: exact to ~1e-10), chained through the linear residual.
    Eigen::MatrixXd jacobian(const Eigen::VectorXd& v) const {
        Eigen::MatrixXd ds(map_.standard_count(), v.size());
        Eigen::VectorXd x = v;
        for (Eigen::Index i = 0; i < v.size(); ++i) {
            const double h = 1e-6 * std::max(1.0, std::abs(v[i]));
            x[i] = v[i] + h;
            const Eigen::VectorXd plus = map_.standard(x);
            x[i] = v[i] - h;
            ds.col(i) = (plus - map_.standard(x)) / (2.0 * h);
            x[i] = v[i];
        }
        Eigen::MatrixXd J(size(), v.size());
        J.topRows(A_.rows()) = A_ * ds;
        J.bottomRows(prior_.size()) = prior_scale_.asDiagonal() * ds;
        return J;
    }

private:
    const PhysicalParametrization& map_;
    Eigen::MatrixXd A_;
    Eigen::VectorXd z_, prior_, prior_scale_;
};

struct Descent {
    Eigen::VectorXd v;
    double cost = 0.0;
    int iterations = 0;
    bool converged = false;
};

// Levenberg-Marquardt with Nielsen's damping update and Marquardt's diagonal scaling.
Descent levenberg_marquardt(const Cost& cost, Eigen::VectorXd v, int max_iterations) {
    Descent d;
    Eigen::VectorXd r = cost.residual(v);
    double f = r.squaredNorm();
    double mu = -1.0, nu = 2.0;
    for (d.iterations = 1; d.iterations <= max_iterations; ++d.iterations) {
        const Eigen::MatrixXd J = cost.jacobian(v);
        const Eigen::MatrixXd H = J.transpose() * J;
        const Eigen::VectorXd g = J.transpose() * r;
        const Eigen::VectorXd scale = H.diagonal().cwiseMax(1e-12 * std::max(1.0, H.diagonal().maxCoeff()));
        if (mu < 0.0) mu = 1e-3;
        if (g.cwiseAbs().maxCoeff() <= 1e-12 * std::max(1.0, f)) {
            d.converged = true;
            break;
        }
        Eigen::MatrixXd damped = H;
        damped.diagonal() += mu * scale;
        const Eigen::VectorXd step = damped.ldlt().solve(-g);
        const Eigen::VectorXd trial = v + step;
        const Eigen::VectorXd r_trial = cost.residual(trial);
        const double f_trial = r_trial.squaredNorm();
        const double predicted = -(2.0 * step.dot(g) + step.dot(H * step));
        const double rho = predicted > 0.0 ? (f - f_trial) / predicted : -1.0;
        if (std::isfinite(f_trial) && rho > 0.0) {
            // A constraint at its bound drives its log variables towards -infinity with ever smaller gains:
            // stop when a step gains less than 1e-10 of the cost.
            const bool small = f - f_trial <= 1e-10 * f || step.norm() <= 1e-12 * (1.0 + v.norm());
            v = trial, r = r_trial, f = f_trial;
            mu *= std::max(1.0 / 3.0, 1.0 - std::pow(2.0 * rho - 1.0, 3));
            nu = 2.0;
            if (small) {
                d.converged = true;
                break;
            }
        } else {
            mu *= nu;
            nu *= 2.0;
            if (mu > 1e16) {  // no step decreases the cost any more: a minimum to rounding
                d.converged = true;
                break;
            }
        }
    }
    d.iterations = std::min(d.iterations, max_iterations);
    d.v = std::move(v);
    d.cost = f;
    return d;
}

}  // namespace

double prior_unit(const std::string& name) {
    std::size_t digits = name.size();
    while (digits > 0 && std::isdigit(static_cast<unsigned char>(name[digits - 1]))) --digits;
    const std::string kind = name.substr(0, digits);
    if (kind == "XX" || kind == "XY" || kind == "XZ" || kind == "YY" || kind == "YZ" || kind == "ZZ" || kind == "IA") return 0.01;
    if (kind == "MX" || kind == "MY" || kind == "MZ") return 0.1;
    return 1.0;
}

PhysicalFit solve_physical(const Eigen::MatrixXd& factor, double sigma2, const Eigen::MatrixXd& regrouping,
                           const std::vector<std::string>& names, const Eigen::VectorXd& unconstrained, const PhysicalSettings& settings) {
    const Eigen::Index c = regrouping.rows(), n = regrouping.cols();
    if (factor.rows() != c + 1 || factor.cols() != c + 1 || static_cast<Eigen::Index>(names.size()) != n || unconstrained.size() != c ||
        (settings.prior.size() != 0 && settings.prior.size() != n) || !(sigma2 > 0.0)) {
        throw std::invalid_argument("solve_physical: sizes of the factor, regrouping, names, solution or prior do not match");
    }
    const PhysicalParametrization map(names, settings.constraint);
    const Eigen::VectorXd prior = settings.prior.size() == n ? settings.prior : Eigen::VectorXd::Zero(n);
    Eigen::VectorXd prior_scale(n);
    for (Eigen::Index i = 0; i < n; ++i) prior_scale[i] = std::sqrt(settings.prior_weight) / prior_unit(names[static_cast<std::size_t>(i)]);
    const Cost cost(factor, sigma2, regrouping, map, prior, prior_scale);

    // The unconstrained solution as standard parameters: the prior moved by the minimum-norm correction
    // that reproduces every identified base value (the others keep the prior's).
    Eigen::VectorXd target = regrouping * prior;
    for (Eigen::Index b = 0; b < c; ++b) {
        if (std::isfinite(unconstrained[b])) target[b] = unconstrained[b];
    }
    const Eigen::VectorXd correction = regrouping.completeOrthogonalDecomposition().solve(target - regrouping * prior);
    PhysicalFit fit;
    fit.constraint = settings.constraint;
    fit.projected_standard = map.standard(map.variables(prior + correction));
    fit.unconstrained_data_cost = cost.data_cost(prior + correction);

    const Descent from_prior = levenberg_marquardt(cost, map.variables(prior), settings.max_iterations);
    const Descent from_projection = levenberg_marquardt(cost, map.variables(prior + correction), settings.max_iterations);
    const bool prior_wins = from_prior.cost <= from_projection.cost;
    const Descent& best = prior_wins ? from_prior : from_projection;
    fit.start = prior_wins ? "prior" : "projected least squares";
    fit.standard = map.standard(best.v);
    fit.base = regrouping * fit.standard;
    fit.data_cost = cost.data_cost(fit.standard);
    fit.prior_cost = cost.prior_cost(fit.standard);
    fit.iterations = best.iterations;
    fit.converged = best.converged;

    for (int link = 0; link < map.link_count(); ++link) {
        const double ratio = map.link_relative_min_eigenvalue(fit.standard, link);
        if (ratio < 1e-6) {
            const std::string& first = names[static_cast<std::size_t>(map.link_first_column(link))];
            fit.active.push_back(fmt::format("link {} {} at its bound (smallest eigenvalue {:.2g} of the largest)", first.substr(2),
                                             settings.constraint == PhysicalConstraint::Full ? "pseudo-inertia" : "inertia about the centre of mass",
                                             ratio));
        }
    }
    for (const int col : map.nonnegative_columns()) {
        const std::string& name = names[static_cast<std::size_t>(col)];
        if (fit.standard[col] < 1e-6 * prior_unit(name)) fit.active.push_back(fmt::format("{} at 0", name));
    }
    return fit;
}

}  // namespace jacobid::identify
