// SPDX-License-Identifier: MIT
#pragma once
// Where a model and the data disagree: a joint's torque residual binned by velocity (sign, near zero),
// position, acceleration and time; its spectrum against the joint angle (periodic content per revolution,
// a least-squares fit of sin/cos(k q) since the angle is irregularly sampled); its autocorrelation.
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

struct JointResidualAnalysis {
    double rms = 0.0;
    std::vector<Bin> velocity, position, acceleration, time;
    std::vector<double> angle_orders, angle_amplitude;  // spectrum vs angle: order k per rev, amplitude N.m
    int dominant_order = 0;
    double dominant_amplitude = 0.0;
    std::vector<double> autocorrelation;  // rho_1..rho_20
    double n_eff = 0.0;
    std::vector<std::string> findings;  // where the disagreement is largest, in words
};

// near_zero: |qd| below which a joint counts as slow (rad/s).
JointResidualAnalysis analyse_residual(const Eigen::VectorXd& residual, const Eigen::MatrixXd& state, const std::vector<double>& t,
                                       double near_zero = 0.05, int max_order = 30);

}  // namespace jacobid::diagnose
