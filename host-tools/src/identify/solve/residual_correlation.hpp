// SPDX-License-Identifier: MIT
#pragma once
// Serial correlation of the decimated LS residuals, kept in streaming form (docs/method.md, "Bias and
// standard deviations, measured"). F_p passes white torque noise up to its cutoff and the rows are taken at
// about 4 samples per cutoff period, so neighbouring residuals are correlated (about 0.6 at lag 1) and the
// residual spectrum at the regressors' low frequencies is about twice its mean: an iid covariance is too
// small by about sqrt(2). The pipeline keeps no rows, so per joint and lag l = 1..L it accumulates
// Gamma_l = sum_t z_t z_{t-l}^T of the augmented rows z = [w, y]; for any solution x the residual
// autocovariance at lag l is then u^T Gamma_l u with u = [x, -1], computed after the solve.
#include <Eigen/Core>
#include <cstddef>
#include <vector>

namespace jacobid::identify {

// Default lag count: F_p's decimated noise correlates over a few rows (sinc(l / 2) for an ideal F_p);
// 16 lags with Bartlett weights recover 98 % of its long-run variance (docs/method.md).
constexpr int kDefaultResidualLags = 16;

// Accumulates Gamma_l of one joint's consecutive rows (a gap or a new segment starts a new accumulator,
// whose sums are then added: no lag crosses it).
// Rows are buffered in blocks and folded in with matrix products (L products of block x (c + 1) by
// block x (c + 1) per block, not L rank-one updates per row), as running_qr.hpp folds its blocks.
class LaggedProducts {
public:
    LaggedProducts(int columns, int lags, int block_rows = 512);
    void add_row(const double* row);
    const std::vector<Eigen::MatrixXd>& gamma();  // lag 1..L at [0..L-1], everything added so far

private:
    void fold();

    int columns_, lags_, block_rows_;
    Eigen::Index history_ = 0;   // rows before the block that are kept for the lags (at most L)
    Eigen::Index buffered_ = 0;  // new rows in the block
    Eigen::MatrixXd rows_;       // [history; block]
    std::vector<Eigen::MatrixXd> gamma_;
};

// Long-run variance over variance of one joint's residual: 1 + 2 sum_l (1 - l / (L + 1)) rho_l (Bartlett,
// i.e. Newey-West, weights: never negative), with rho_l = u^T Gamma_l u / gamma_0 and gamma_0 = ||e||^2.
// Returns 1 without lags or residual.
double long_run_variance_factor(const std::vector<Eigen::MatrixXd>& gamma, const Eigen::VectorXd& u, double gamma0);

// The lag-l residual autocorrelations rho_1..rho_L (for reports and tests).
std::vector<double> residual_autocorrelation(const std::vector<Eigen::MatrixXd>& gamma, const Eigen::VectorXd& u, double gamma0);

// sum over |t - u| <= lags of (1 - |t - u| / (lags + 1)) x_t . y_u, over the rows of x and y (same shape): the
// Bartlett-weighted band of cross products every HAC sum below is made of.
double bartlett_cross_sum(const Eigen::Ref<const Eigen::MatrixXd>& x, const Eigen::Ref<const Eigen::MatrixXd>& y, int lags);

// Newey-West estimate of Var(sum_t g_t) for a serially correlated series g (a score, zero-mean by
// construction, so not centred): sum_{|l| <= L} (1 - |l| / (L + 1)) Gamma_l with Gamma_l = sum_t g_t g_{t-l},
// i.e. bartlett_cross_sum(g, g, L). Bartlett weights keep it non-negative; L = 0 is the independent-rows sum of
// squares. The torque delay's std uses it on its per-row score (docs/method.md, "Torque delay").
double bartlett_long_run_variance(const Eigen::Ref<const Eigen::VectorXd>& g, int lags);

// Newey and West's (1994) lag rule for Bartlett weights, floor(4 (n / 100)^(2/9)) for n rows: 4 lags for
// 100 to 272 rows, 7 for 2 000. The estimate's downward bias grows with lags / rows and its spread with
// sqrt(lags / rows), so a score of a few hundred rows needs few lags (docs/method.md, "Torque delay").
int newey_west_lags(std::size_t rows);

}  // namespace jacobid::identify
