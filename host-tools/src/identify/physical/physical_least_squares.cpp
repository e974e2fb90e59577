// SPDX-License-Identifier: MIT
#include "identify/physical/physical_least_squares.hpp"

#include <fmt/core.h>

#include <Eigen/Cholesky>
#include <Eigen/QR>
#include <cctype>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace jacobid::identify {
namespace {

// Smallest anchor weight (in the prior's units): negligible beside any chi^2, enough to fix the directions
// nothing else decides.
constexpr double kAnchorWeight = 1e-9;

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
    const double inv_sigma = 1.0 / std::sqrt(sigma2);
    const Eigen::MatrixXd A = inv_sigma * factor.topLeftCorner(c + 1, c) * regrouping;
    const Eigen::VectorXd z = inv_sigma * factor.col(c);
    auto data_cost = [&](const Eigen::VectorXd& s) { return (A * s - z).squaredNorm(); };
    const Eigen::VectorXd given = settings.prior.size() == n ? settings.prior : Eigen::VectorXd::Constant(n, std::numeric_limits<double>::quiet_NaN());
    Eigen::VectorXd start_prior = given;  // the prior, 0 where none is given
    for (Eigen::Index i = 0; i < n; ++i) {
        if (!std::isfinite(start_prior[i])) start_prior[i] = 0.0;
    }

    // The unconstrained solution as standard parameters: the prior moved by the minimum-norm correction
    // that reproduces every identified base value (the others keep the prior's).
    Eigen::VectorXd target = regrouping * start_prior;
    for (Eigen::Index b = 0; b < c; ++b) {
        if (std::isfinite(unconstrained[b])) target[b] = unconstrained[b];
    }
    const Eigen::VectorXd correction = regrouping.completeOrthogonalDecomposition().solve(target - regrouping * start_prior);
    PhysicalFit fit;
    fit.constraint = settings.constraint;
    fit.projected_standard = map.standard(map.variables(start_prior + correction));
    fit.unconstrained_data_cost = data_cost(start_prior + correction);

    // The anchor of every standard parameter: its prior value, weight w / u_i^2; without a prior, the
    // projected unconstrained solution with the negligible weight kAnchorWeight / u_i^2 (also the floor of
    // w), so that a direction neither the log nor a prior decides stays where the data left it instead of
    // drifting outwards with the barrier, while every direction the log excites is left to the data.
    Eigen::VectorXd anchor(n), anchor2(n);
    for (Eigen::Index i = 0; i < n; ++i) {
        const double u = prior_unit(names[static_cast<std::size_t>(i)]);
        anchor[i] = std::isfinite(given[i]) ? given[i] : fit.projected_standard[i];
        anchor2[i] = (std::isfinite(given[i]) ? std::max(settings.prior_weight, kAnchorWeight) : kAnchorWeight) / (u * u);
    }
    // The cost as s^T Q s - 2 c^T s + const: A = R K / sigma, Q = A^T A + diag(w / u^2), c = A^T z + diag(w / u^2) p.
    Eigen::MatrixXd Q = A.transpose() * A;
    Q.diagonal() += anchor2;
    const Eigen::VectorXd linear = A.transpose() * z + anchor2.cwiseProduct(anchor);

    // Interior point from the projected solution (strictly feasible: eigenvalues raised to 1e-6 of the largest).
    BarrierSettings barrier;
    barrier.gap = settings.gap;
    const BarrierResult solved = minimise_with_lmis(Q, linear, map.constraint_blocks(), fit.projected_standard, barrier);
    fit.standard = solved.x;
    fit.base = regrouping * fit.standard;
    fit.data_cost = data_cost(fit.standard);
    fit.prior_cost = (fit.standard - anchor).cwiseAbs2().dot(anchor2);
    fit.iterations = solved.newton_steps;
    fit.converged = solved.converged;
    fit.duality_gap = solved.gap;

    for (int link = 0; link < map.link_count(); ++link) {
        const double ratio = map.link_relative_min_eigenvalue(fit.standard, link);
        if (ratio < 1e-5) {
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
