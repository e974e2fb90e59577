// SPDX-License-Identifier: MIT
#pragma once
// Solution and statistics of the identification LS problem Y = W X + rho from triangular factors of
// [W Y] (running_qr.hpp), one per joint, so that ordinary, weighted (Gautier) and reduced (essential
// parameters) problems are all solved without touching the data again.
//
// Statistics (docs/method.md, "Identification"): sigma_rho^2 = ||Y - W X||^2 / (r - c), C_XX = sigma_rho^2 (W^T W)^-1,
// %sigma_r = 100 sigma_X / |X|, cond(W), relative error norm ||Y - W X|| / ||Y||.
// Rank: columns of W that are zero (to rounding) and directions in which the column-normalized W is
// numerically singular are reported, with the parameter combinations W cannot see; the LS is then solved
// for a maximal identifiable subset (column-pivoted QR) and the others are marked not identified, never
// returned as a silent number.
#include <Eigen/Dense>
#include <string>
#include <vector>

namespace jacobid::identify {

// One system: per-joint augmented factors [W_j Y_j] (c + 1 columns) and their row counts.
struct JointFactors {
    std::vector<Eigen::MatrixXd> r;
    std::vector<std::size_t> rows;
    // Per joint, the lagged products Gamma_1..Gamma_L of its consecutive augmented rows
    // (residual_correlation.hpp); empty: not accumulated (only the iid std is then available).
    std::vector<std::vector<Eigen::MatrixXd>> lagged;
};

// How sigma_X is computed (docs/method.md, "Bias and standard deviations, measured"):
//  - Pooled: sigma_rho^2 (W^T W)^-1 of the problem solved, one residual variance for every row, rows
//    independent (the textbook formula; too large for a quiet joint next to a noisy one, too small for the
//    serially correlated rows F_p and the decimation leave);
//  - JointHac: the sandwich (W^T S W)^-1 (sum_j s_j^4 lrv_j W_j^T W_j) (W^T S W)^-1 with S the weights
//    s_j^2, lrv_j = sigma_j^2 f_j joint j's own residual variance times its long-run variance factor
//    (Bartlett over JointFactors::lagged). Exact when the residuals are independent between joints and the
//    regressors vary slowly over the residuals' correlation length (they lie below the motion bandwidth,
//    F_p keeps 5 x more). Without lagged products f_j = 1 (per-joint variances only).
enum class StdMethod { Pooled, JointHac };
const char* to_string(StdMethod m);

struct Unidentifiable {
    std::vector<int> parameters;       // indices into the full parameter list
    std::vector<double> coefficients;  // W * a = 0 (to the rank tolerance) with a = coefficients (max |a| = 1)
    bool zero_column = false;          // a single parameter whose regressor column is zero
};

struct LsSolution {
    std::vector<std::string> names;
    Eigen::VectorXd x;                 // all parameters; NaN where not identified
    Eigen::VectorXd std_dev;           // sigma_X (NaN where not identified)
    Eigen::VectorXd rel_std_percent;   // %sigma_r
    // C_XX over all parameters (the std's own method: pooled or joint-HAC); rows and columns of parameters not
    // identified are NaN. What a derived quantity's std needs (the payload's centre of mass m c / m).
    Eigen::MatrixXd covariance;
    std::vector<bool> identified;      // false: dropped (rank) or removed (essential)
    std::vector<bool> removed;         // removed as non-essential
    std::size_t equations = 0;
    int identified_count = 0;
    int rank = 0;                      // numerical rank of W over the active columns
    double cond = 0.0;                 // cond(W) (2-norm) over the identified columns
    double residual_norm = 0.0;        // ||Y - W X|| (weighted when weights are used)
    double y_norm = 0.0;               // ||Y||
    double relative_error_norm = 0.0;  // ||Y - W X|| / ||Y||
    double sigma_rho = 0.0;
    std::vector<double> joint_residual_rms;  // unweighted, per joint
    std::vector<double> joint_weights;       // 1 / sigma_j when weighted, else 1
    StdMethod std_method = StdMethod::Pooled;
    int std_lags = 0;                             // lags of the long-run factors (0: none)
    std::vector<double> joint_sigma;              // per joint residual std (dof-corrected), JointHac
    std::vector<double> joint_long_run_factors;   // per joint long-run / plain variance (JointHac)
    std::vector<double> joint_lag1_correlation;   // per joint residual autocorrelation at lag 1 (JointHac)
    std::vector<Unidentifiable> unidentifiable;
    bool weighted = false;
};

struct SolveOptions {
    bool weighted = false;            // Gautier's per-joint weighting by 1 / sigma_j from an OLS pass
    double rank_tolerance = 1e-7;     // singular values of the column-normalized W below tol * max are null
    std::vector<bool> active;         // columns to use; empty: all
    StdMethod std_method = StdMethod::Pooled;
    // Per joint noise std known from elsewhere (identify --period: the period-to-period spread); when
    // weighted, joint j is weighted by 1 / joint_noise[j] instead of 1 / sigma_j of the OLS residuals
    // (which also hold model error). Empty: from the residuals.
    std::vector<double> joint_noise;
};

// The triangular factor [R z] of every joint's rows stacked, joint j's scaled by scale[j] (the weights of a
// solution: LsSolution::joint_weights), over all columns.
Eigen::MatrixXd stacked_factor(const JointFactors& factors, const std::vector<double>& scale);

// Solves the (weighted) LS problem for the active columns of the per-joint factors.
LsSolution solve_least_squares(const JointFactors& factors, const std::vector<std::string>& names, const SolveOptions& options = {});

// InputError naming `source` and the first identified parameter whose value is not finite: such
// a result is never written (the log held values whose squares overflowed the solve).
void require_finite_solution(const LsSolution& solution, const std::string& source);

struct EssentialStep {
    std::string removed;           // parameter removed at this step ("" for the full model)
    double removed_rel_std = 0.0;  // its %sigma_r before removal
    double relative_error_norm = 0.0;
    int parameters = 0;
};

struct EssentialResult {
    LsSolution solution;  // the final essential model
    std::vector<EssentialStep> steps;
};

// Iteratively removes the parameter with the largest %sigma_r above `threshold_percent` and re-solves.
EssentialResult essential_parameters(const JointFactors& factors, const std::vector<std::string>& names, double threshold_percent,
                                     const SolveOptions& options = {});

}  // namespace jacobid::identify
