// SPDX-License-Identifier: MIT
#pragma once
// Physically consistent least squares (identify --physical / --semi-physical; docs/method.md, "Physically
// consistent identification"): the standard parameters s that minimise
//     ||R K s - z||^2 / sigma^2  +  w sum_i ((s_i - p_i) / u_i)^2
// over the physically possible set (physical_parametrization.hpp), where [R z] is the triangular factor of
// the (weighted) identification problem over the base parameters (so the cost does not grow with the log),
// K the regrouping (base = K s), p the prior standard values (the description's URDF/CAD inertials; the
// sum runs over the parameters that have one), u_i a unit per kind and w the prior weight. The data term decides every direction the log excites; the small
// prior term only picks, among the sets that fit equally well, the one nearest the prior, so the standard
// parameters come out complete (a URDF can be written from them).
// The cost is quadratic in s and the constraints are linear matrix inequalities in s, so the problem is
// convex: an interior-point method (lmi_barrier.hpp) finds its global minimum with a certified gap, started
// from the unconstrained solution moved to the nearest possible point (physical_parametrization.hpp).
#include <Eigen/Core>
#include <string>
#include <vector>

#include "identify/physical/physical_parametrization.hpp"

namespace jacobid::identify {

struct PhysicalSettings {
    PhysicalConstraint constraint = PhysicalConstraint::Full;
    double prior_weight = 1e-3;  // w
    Eigen::VectorXd prior;       // p, standard order; NaN (or empty: all) for no prior term on that parameter
    double gap = 1e-6;  // duality-gap bound at which the interior point stops (chi^2 units)
};

struct PhysicalFit {
    PhysicalConstraint constraint = PhysicalConstraint::Full;
    Eigen::VectorXd standard;  // s
    Eigen::VectorXd base;      // K s
    Eigen::VectorXd projected_standard;  // the unconstrained solution moved to the nearest possible point
    double data_cost = 0.0;             // ||R K s - z||^2 / sigma^2 at s
    double unconstrained_data_cost = 0.0;  // the same at the unconstrained LS solution
    double prior_cost = 0.0;
    int iterations = 0;        // Newton steps
    bool converged = false;    // the duality-gap bound reached PhysicalSettings::gap
    double duality_gap = 0.0;  // bound on cost - optimal cost
    std::vector<std::string> active;  // constraints at their bound (relative eigenvalue below 1e-5), in words
};

// What identify reports of a consistent fit (MethodResult::physical).
struct PhysicalReport {
    PhysicalFit fit;
    double prior_weight = 0.0;
    double seconds = 0.0;  // solve time
    std::vector<std::string> standard_names;
    Eigen::VectorXd unconstrained_x;  // the least-squares base values it replaced (NaN where not identified)
    // Base parameters the log did not identify (removed as unexcited, or by --essential): their consistent
    // values come from the prior alone.
    std::vector<std::string> not_identified;
};

// The kind's unit u_i in the prior term: 0.01 kg.m^2 (inertias, rotor inertias), 0.1 kg.m (first moments),
// 1 kg (masses), 1 N.m (friction, offsets; per rad/s for viscous).
double prior_unit(const std::string& standard_name);

// factor: (c+1) x (c+1) upper triangular [R z] over the c base parameters; sigma2: the residual variance that
// scales it (1 for a problem already weighted by 1 / sigma_j); regrouping: c x standard (base = K s);
// unconstrained: the LS solution over the base parameters (NaN where not identified). std::invalid_argument
// for sizes that do not match.
PhysicalFit solve_physical(const Eigen::MatrixXd& factor, double sigma2, const Eigen::MatrixXd& regrouping,
                           const std::vector<std::string>& standard_names, const Eigen::VectorXd& unconstrained,
                           const PhysicalSettings& settings);

}  // namespace jacobid::identify
