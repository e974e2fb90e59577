// SPDX-License-Identifier: MIT
#pragma once
// Per-sample regressor storage shared by the robot models: D(q, qd, qdd) with tau = D X, one row per
// joint, one column per base parameter. Fixed-size so that evaluating it allocates nothing; a model whose
// options switch parameters on and off uses the first parameter_count() columns.
#include <Eigen/Core>

namespace jacobid::robot {

template <int Joints, int MaxParameters>
using RegressorMatrix = Eigen::Matrix<double, Joints, MaxParameters, Eigen::RowMajor>;

template <int Joints>
using JointVector = Eigen::Matrix<double, Joints, 1>;

}  // namespace jacobid::robot
