// SPDX-License-Identifier: MIT
#pragma once
// Statistics of filtered, decimated residuals, which are correlated: the autocorrelation, the effective
// sample size it implies, and the chi-square tail used by the selection's significance test.
#include <Eigen/Core>
#include <vector>

namespace jacobid::diagnose {

// Sample autocorrelation rho_1..rho_max_lag of a series (mean removed).
std::vector<double> autocorrelation(const Eigen::VectorXd& x, int max_lag);

// Effective sample size of n correlated samples (Bartlett): n / (1 + 2 sum_k rho_k), the sum running over
// the initial positive run of rho_k (lags up to min(n / 4, 200)); clamped to [1, n].
double effective_sample_size(const Eigen::VectorXd& residual);

// P(chi^2_dof > x) for an integer dof >= 1 (exact: erfc for the odd start, then the recursion
// Q(a + 1, y) = Q(a, y) + y^a e^-y / Gamma(a + 1) with a = dof / 2, y = x / 2).
double chi_square_survival(double x, int dof);

}  // namespace jacobid::diagnose
