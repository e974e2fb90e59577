// SPDX-License-Identifier: MIT
#pragma once
// Normal equations of a subset of regressor columns, G = W^T W, b = W^T Y, yy = Y^T Y, and their solution:
// any column subset, joint weighting or held-out split is then a small dense solve without the rows. Shared
// by the diagnosis's model search (diagnose/blocked_grams.hpp) and the Coulomb smoothing choice
// (coulomb_smoothing.hpp).
#include <Eigen/Core>

namespace jacobid::identify {

struct GramSums {
    Eigen::MatrixXd G;
    Eigen::VectorXd b;
    double yy = 0.0;
    double rows = 0.0;
};

struct SubsetFit {
    Eigen::VectorXd x;
    Eigen::MatrixXd inverse;  // G^-1 (the covariance up to sigma^2)
    double rss = 0.0;         // at the solution
    bool ok = false;          // false: G singular over the subset
};

// LS solution of the normal equations (columns scaled to unit diagonal first; a pivot below 1e-10 of its
// diagonal means the subset is collinear: ok = false).
SubsetFit solve_subset(const GramSums& sums);
// Minimum-norm LS solution: solve_subset's when the columns are independent, otherwise a truncated
// eigen-decomposition of the scaled G (a trajectory that leaves a combination unexcited still predicts
// held-out rows in the span it does excite).
Eigen::VectorXd solve_minimum_norm(const GramSums& sums);
// Sum of squared prediction errors of x on other rows: yy - 2 x.b + x^T G x.
double prediction_sse(const GramSums& held_out, const Eigen::VectorXd& x);

}  // namespace jacobid::identify
