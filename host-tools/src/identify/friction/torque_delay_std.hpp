// SPDX-License-Identifier: MIT
#pragma once
// The torque delay's standard deviation with the rows' serial correlation (docs/method.md, "Torque delay").
//
// The estimate minimizes RSS(d) = sum_t sum_j e_jt(d)^2 over the decimated rows t of every joint j, i.e. it
// solves the score equation S(d) = RSS'(d) / 2 = sum_t g_t = 0 with g_t = sum_j e_jt de_jt/dd. To first order
// d^ - d0 = -S(d0) / S'(d0) with S' = RSS'' / 2, so Var(d^) = Var(S) / (RSS'' / 2)^2 (the sandwich). Var(S)
// is the Newey-West long-run variance of g over the rows: F_p passes the torque noise up to its cutoff and the
// rows are taken a few per cutoff period, so neighbouring g_t are correlated, which the independent-rows
// formula 2 sigma^2 / RSS'' ignored (its std was 2.1-2.2 x too small; docs/excite.md, "Is the predicted std
// honest?"). The residuals are those of a fit (the parameters and the delay itself took out part of the noise
// the score sees): a leverage factor restores it.
#include <cstddef>
#include <vector>

#include "identify/pipeline/row_collector.hpp"
#include "identify/solve/least_squares.hpp"

namespace jacobid::identify {

// The fit of the torque read `shift` samples later: one point of the search's one-sample grid.
struct ShiftedFit {
    int shift = 0;
    const LsSolution* solution = nullptr;
};

struct DelayScoreVariance {
    double variance = 0.0;         // Var(S), N.m^2 x (N.m / s)^2
    int lags = 0;                  // Bartlett lags (newey_west_lags of the rows)
    double leverage_factor = 1.0;  // what the fit's leverage took out of the HAC sum, put back (>= 1)
    std::size_t rows = 0;          // decimated rows (time instants); 0: not available
};

// Var(S) at the estimate `delay` (s) from the fits at the grid's minimum and its two neighbours (`around`:
// shifts s - 1, s, s + 1), the first identification's rows and filtered torque (`rows`) and RSS'' there
// (`curvature`, N.m^2 / s^2). rows == 0 in the result when the rows were not kept or a shifted sample falls
// outside the filtered torque.
DelayScoreVariance torque_delay_score_variance(const RowCollector& rows, const ShiftedFit (&around)[3], double sample_period, double delay,
                                               double curvature);

// The HAC sum's expected shortfall for scores g_t = sum_j a_jt e_jt of fitted residuals, as a factor >= 1
// (docs/method.md, "Torque delay"): the parameters' fit (e = (I - P) eps, P = W A^-1 W^T S, A = W^T S W with
// S the joints' weights s_j^2) and the delay's own (e is taken at the estimate, which removes the noise along
// de/dd) take the noise's long-run variance out of the rows where a is large. Noise per joint locally white
// with long-run variance lambda_j per row; `a` and `de` (n x joints): the score's factor and the uncorrected
// de/dd; `w`: per joint n x k (identified columns); `s2`: s_j^2. Bartlett weights over `lags`.
double hac_leverage_factor(const Eigen::MatrixXd& a, const Eigen::MatrixXd& de, const std::vector<Eigen::MatrixXd>& w,
                           const std::vector<double>& s2, const std::vector<double>& lambda, int lags, double curvature_half);

}  // namespace jacobid::identify
