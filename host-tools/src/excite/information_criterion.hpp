// SPDX-License-Identifier: MIT
#pragma once
// The criteria `jacobid excite` optimizes, as functions of the base regressor W stacked over samples (rows
// sample-major, joint-minor: row i * joints + j is joint j at sample i), with their gradient dF/dW
// (docs/excite.md, "The criterion").
//
// Information criteria (what identify's WLS estimate will know, docs/excite.md "Predicted std"):
//   A = gamma sum_i W_i^T S^-1 W_i, the information matrix of the base parameters, S = diag(sigma_j^2) the
//   per-joint torque noise variance, gamma the log samples each optimizer sample stands for (the rate times
//   the duration over the samples: the sum approximates the integral over every sample identify's F_p and
//   decimation keep the information of: docs/excite.md, "The criterion and the limits"), C = A^-1 the predicted
//   covariance of the WLS estimate;
//   - d-optimal:  -log det A;
//   - a-relative: log sum_k C_kk / s_k^2, s_k the prior scale of parameter k (parameter_scales.hpp);
//   - e-relative: a smooth maximum (log-sum-exp, sharpness kMaxSharpness in log space) of log C_kk / s_k^2;
//   - i-optimal:  log trace(M C), M the reference motion's information per sample (InformationModel::reference):
//     the mean over that motion of the predicted variance of the model's torque, in units of each joint's noise
//     variance; what a validation on that motion measures of the estimate's noise (docs/excite.md).
//   Gradients: dA = gamma (dW^T S^-1 W + W^T S^-1 dW) and dC = -C dA C give, for F = f(C_kk),
//   dF/dW = -2 gamma S^-1 W C diag(df/dC_kk) C, for i-optimal -2 gamma S^-1 W C M C / trace(M C), and for
//   d-optimal dF/dW = -2 S^-1 W (W^T S^-1 W)^-1.
// Column-normalised criteria (kept for comparison; blind to the size of the motion):
//   - cond:   log cond(W_s), W_s = W diag(1 / ||w_k||);
//   - logdet: -log det(W_s^T W_s).
// A rank-deficient W gives kRankDeficient and a zero gradient (the worst value, not a NaN for the optimizer).
#include <Eigen/Core>
#include <limits>
#include <optional>
#include <string>

namespace jacobid::excite {

enum class Criterion { Cond, LogDet, DOptimal, ARelative, ERelative, IOptimal };
const char* to_string(Criterion c);
std::optional<Criterion> criterion_from_string(const std::string& name);
// Whether the criterion weighs the noise and the size of the motion (the information criteria).
bool is_information_criterion(Criterion c);

inline constexpr double kRankDeficient = 1e30;
inline constexpr double kMaxSharpness = 20.0;  // e-relative: over-estimate of the max <= log(parameters) / 20

// What the information criteria weigh: per-joint noise, per-parameter prior scale, the samples' weight, and
// which parameters the design is for.
struct InformationModel {
    Eigen::VectorXd noise_std;   // per joint, N.m (> 0)
    Eigen::VectorXd scale;       // per parameter designed for (base parameter, or projection column), its prior scale (> 0)
    double sample_weight = 1.0;  // gamma: log samples per criterion sample
    // Empty: the criteria are of the base parameters themselves. Else (base parameters x m) the criteria are of
    // the m parameters phi whose regressor is W K, the others held known: `excite --payload`'s K is the
    // regrouping's columns of the last link's ten standard parameters (payload_target.hpp), so the information
    // matrix is K^T A K and dF/dW = dF/d(WK) K^T.
    Eigen::MatrixXd projection;
    // i-optimal: M = (1 / N) sum over the reference motion's N samples of W_i^T S^-1 W_i (base parameters x base
    // parameters, symmetric positive semi-definite; reference_information() in motion_information.hpp).
    Eigen::MatrixXd reference;
    // Empty: each sample's regressor counts as it is. Else (samples x samples, symmetric: periodic_lowpass.hpp)
    // identify's F_p along the samples of one period: the information criteria are of F W, each joint's rows
    // filtered (what identify's decimated rows keep), and dF/dW = F dF/d(FW).
    Eigen::MatrixXd time_filter;
};

// F(W) and, when `dW` is not null, dF/dW (W's shape). `model` is read by the information criteria only, except
// its projection, which every criterion applies (cond and logdet then of W K).
double evaluate_criterion(Criterion criterion, const Eigen::MatrixXd& W, int joints, const InformationModel& model, Eigen::MatrixXd* dW);

// The information matrix gamma sum_i W_i^T S^-1 W_i of stacked rows W (as above).
Eigen::MatrixXd information_matrix(const Eigen::MatrixXd& W, int joints, const Eigen::VectorXd& noise_std, double sample_weight);

// What an information matrix predicts for the WLS estimate: per base parameter its std (the square root of
// C_kk) and its relative std (std / scale); identifiable false (and the stds infinite) when A is singular.
struct Prediction {
    Eigen::VectorXd std_dev, relative_std;
    double log_det = 0.0;  // log det A
    bool identifiable = false;
    // The largest relative std and its parameter (index), over every base parameter.
    double worst_relative_std = 0.0;
    int worst = -1;
    // With a reference information M (i-optimal): sqrt(trace(M C)), the predicted rms error of the model's torque
    // over the reference motion from the estimate's noise, in units of each joint's noise std (NaN: no reference).
    double reference_rms = std::numeric_limits<double>::quiet_NaN();
};
Prediction predict(const Eigen::MatrixXd& information, const Eigen::VectorXd& scale, const Eigen::MatrixXd* reference = nullptr);

}  // namespace jacobid::excite
