// SPDX-License-Identifier: MIT
#pragma once
// Where a model and the data disagree: a joint's torque residual binned by velocity (sign, near zero),
// position, acceleration and time; its spectrum against the joint angle (periodic content per revolution,
// a least-squares fit of sin/cos(k q) since the angle is irregularly sampled); its autocorrelation; and its
// split by motion state (at rest / reversing / moving), which locates friction-at-rest gaps before any
// candidate effect is tried.
#include <Eigen/Dense>
#include <string>
#include <vector>

namespace jacobid::diagnose {

struct Bin {
    std::string label;
    double low = 0.0, high = 0.0;
    std::size_t count = 0;
    double mean = 0.0, rms = 0.0;
};

// Motion states of a row: "moving" when |qd| >= near_zero; below it, "reversing" when |qdd| >= near_zero /
// 0.2 s (the joint crosses the near-zero band in under 0.4 s: passing through zero velocity), else "at rest".
struct MotionStateBin {
    std::string state;      // "at rest", "reversing", "moving"
    std::size_t count = 0;
    double mean = 0.0, rms = 0.0;  // N.m
    double row_share = 0.0;        // of the joint's rows
    double energy_share = 0.0;     // of the joint's sum of squared residuals
};

struct JointResidualAnalysis {
    double rms = 0.0;
    std::vector<Bin> velocity, position, acceleration, time;
    std::vector<MotionStateBin> motion;  // at rest, reversing, moving (always three)
    std::vector<double> angle_orders, angle_amplitude;  // spectrum vs angle: order k per rev, amplitude N.m
    int dominant_order = 0;
    double dominant_amplitude = 0.0;
    std::vector<double> autocorrelation;  // rho_1..rho_20
    double n_eff = 0.0;
    std::vector<std::string> findings;  // where the disagreement is largest, in words
};

// A residual whose effective sample size is below a fifth of its rows: structure is left in it (the bound of
// the "strongly correlated" finding and of the "noise floor" verdict). False for NaN (an exactly zero residual).
inline bool strongly_correlated(const JointResidualAnalysis& a, std::size_t rows) { return a.n_eff < 0.2 * static_cast<double>(rows); }

// near_zero: |qd| below which a joint counts as slow (rad/s).
JointResidualAnalysis analyse_residual(const Eigen::VectorXd& residual, const Eigen::MatrixXd& state, const std::vector<double>& t,
                                       double near_zero = 0.05, int max_order = 30);

}  // namespace jacobid::diagnose
