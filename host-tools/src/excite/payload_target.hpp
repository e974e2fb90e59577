// SPDX-License-Identifier: MIT
#pragma once
// `jacobid excite --payload` (docs/excite.md, "Payload designs"): a design for the ten inertial parameters of a
// payload on the last link with the arm held known, what `jacobid payload` estimates (payload/payload_estimate.hpp).
//   - The parameters designed for: phi, the payload's standard parameters XX XY XZ YY YZ ZZ MX MY MZ M about the
//     last link's frame (they add to the link's own). Their regressor is W K, K the regrouping's columns of the
//     last link's ten standard parameters (base = regrouping * standard), so their information is K^T A K, A the
//     base parameters' (InformationModel::projection).
//   - The prior: a point mass of `mass` kg at `com` (m, the last link's frame), as the user expects it; its
//     parameters add to the description's for the model torque (the torque limits) and give the prior scales.
//   - Prior scales (what the relative std is relative to): s_k = max(|phi_k|, P_k / 10), P_k of the kind as in
//     parameter_scales.hpp with the payload's mass m and size l = max(|com|, 0.1 m) (a tool's reach from the
//     flange): m for M, m l for the first moments, m l^2 for the inertias.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "excite/information_criterion.hpp"
#include "robot/robot_model.hpp"

namespace jacobid::excite {

inline constexpr double kPayloadMinSize = 0.1;  // m: the payload's length scale at least (P_k above)

struct PayloadTarget {
    Eigen::MatrixXd projection;        // base parameters x 10: K
    Eigen::VectorXd prior;             // 10: the point mass's standard parameters, XX..M
    Eigen::VectorXd scales;            // 10
    std::vector<std::string> names;    // XX .. M
    double mass = 0.0;
    Eigen::Vector3d com = Eigen::Vector3d::Zero();
    int link = 0;                      // the last link (1-based joint number)
};

// InputError naming --payload when the model has no per-link standard parameters (mdh or urdf needed), and
// --payload-mass / --payload-com for a mass that is not > 0 or a centre of mass that is not 3 finite values.
PayloadTarget make_payload_target(const robot::RobotModel& model, double mass, const std::vector<double>& com);

// The model's parameters with the payload's prior added to the last link's (the loaded robot's torque).
Eigen::VectorXd with_payload(const Eigen::VectorXd& base_values, const PayloadTarget& payload);

// What an information matrix of the base parameters predicts for the payload's ten (K^T A K).
Prediction predict_payload(const Eigen::MatrixXd& base_information, const PayloadTarget& payload);

// The predicted std of what `jacobid payload` prints (mass, centre of mass, inertia about it: payload_inertia.hpp's
// inertial_names), at the prior, by the delta method from the predicted covariance of the ten (C = (K^T A K)^-1).
// Infinite when the prediction is not identifiable.
Eigen::VectorXd predicted_inertial_std(const Eigen::MatrixXd& base_information, const PayloadTarget& payload);

}  // namespace jacobid::excite
