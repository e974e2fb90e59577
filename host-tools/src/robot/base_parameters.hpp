// SPDX-License-Identifier: MIT
#pragma once
// Base parameters computed numerically (Gautier 1991): the standard regressor W is stacked over random
// states; the rank comes from a QR decomposition with column pivoting, and the base set is chosen by
// walking the columns in a fixed priority order (link by link, YY after ZZ, rotor inertia after the link's
// inertia) and keeping every column that is independent of those kept before it. Each dropped column is
// then an exact combination of kept ones, w_d = sum_b beta_bd w_b, so that
//   base_b = X_b + sum_d beta_bd X_d        (Khalil's regrouping, e.g. ZZ1R = ZZ1 + IA1 + 0.25 M2).
// Columns that are identically zero (parameters with no effect on the torques) are listed separately.
#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

namespace jacobid::robot {

struct BaseParameterSet {
    std::vector<int> base_columns;        // standard column of each base parameter, in base order
    std::vector<std::string> base_names;  // standard name + "R" when other parameters are regrouped into it
    Eigen::MatrixXd regrouping;           // base x standard: base = regrouping * standard
    std::vector<int> no_effect;           // standard columns that never change the torques
    int pivoted_qr_rank = 0;              // rank of W from the pivoted QR (equals base_columns.size())
};

struct BaseParameterSettings {
    int states = 0;                // random states; 0: enough for 3 rows per standard parameter
    double tolerance = 1e-8;       // relative residual below which a column counts as dependent
    double coefficient_zero = 1e-9;  // |beta| below this is printed and applied as exactly 0
    unsigned seed = 12345;
};

// Fills the joint_count x standard_count regressor at the state (q, qd, qdd).
using StandardRegressorFunction = std::function<void(const double* q, const double* qd, const double* qdd, Eigen::Ref<Eigen::MatrixXd> W)>;

// priority: standard columns in the order in which they are preferred as base parameters (all columns).
// prismatic[j]: joint j translates (its random positions stay within +-1 m instead of +-pi rad).
BaseParameterSet compute_base_parameters(int joint_count, const std::vector<std::string>& standard_names, const std::vector<int>& priority,
                                         const std::vector<bool>& prismatic, const StandardRegressorFunction& regressor,
                                         const BaseParameterSettings& settings = {});

// "ZZ1R = ZZ1 + IA1 + 0.25*M2", one line per base parameter.
std::vector<std::string> regrouping_relations(const BaseParameterSet& base, const std::vector<std::string>& standard_names);

}  // namespace jacobid::robot
