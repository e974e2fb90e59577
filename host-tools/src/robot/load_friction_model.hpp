// SPDX-License-Identifier: MIT
#pragma once
// A robot model whose Coulomb friction grows with the load the joint carries (docs/method.md,
// "Load-dependent Coulomb friction"): the nominal model's columns followed by one column FCLj per loaded
// joint, on the joint's own row,
//   abs:    |g_j(q)|   s_j(qd_j)       square: g_j(q)^2 s_j(qd_j)
// with s_j the joint's Coulomb sign function (the FCj column's) and g_j(q) the gravity torque of the joint
// under a REFERENCE rigid body (the description's parameters: URDF inertials or `parameters:`), fixed when
// the model is built. A gear's friction grows with the torque it transmits; the gravity part of it is known
// from the reference and keeps the model linear in FCLj (the torque the fit itself predicts would not).
// A joint whose gravity torque is identically 0 (a vertical axis) gets no column. Stateless: the columns are
// sign-function columns (RobotModel::coulomb_column_indices lists FCLj beside FCj) and the simulator
// applies them through the forward dynamics like any other column.
#include <memory>
#include <string>
#include <vector>

#include "jacobid/robot/coulomb_sign.hpp"
#include "robot/model_extension.hpp"

namespace jacobid::robot {

enum class CoulombLoad { none, abs, square };
const char* to_string(CoulombLoad law);

class LoadFrictionModel final : public ModelExtension {
public:
    // `reference`: nominal parameter vector whose gravity torques scale the friction (friction and offset
    // entries are ignored); `signs`: each joint's Coulomb sign function. Throws std::invalid_argument when
    // no joint carries any gravity torque under the reference (a planar robot, no inertial parameters).
    LoadFrictionModel(std::unique_ptr<RobotModel> nominal, CoulombLoad law, const Eigen::VectorXd& reference, std::vector<CoulombSign> signs);

    void regressor(const double* q, const double* qd, const double* qdd, Eigen::Ref<Eigen::MatrixXd> D) const override;
    void coulomb_columns(const double* q, const double* qd, const double* qdd, Eigen::Ref<Eigen::MatrixXd> D) const override;
    bool inverse_dynamics(const double* q, const double* qd, const double* qdd, const Eigen::VectorXd& X, double* tau) const override;
    std::unique_ptr<DirectForwardDynamics> articulated_body(const Eigen::VectorXd& X) const override;

    // The joints (0-based) that have an FCLj column, in column order after the nominal's.
    const std::vector<int>& loaded_joints() const { return loaded_; }
    // Each joint's load factor at q (|g_j| or g_j^2 of the reference gravity torque), which its column multiplies s_j by.
    void load_factors(const double* q, double* factors) const;
    // s_j(velocity), joint j's Coulomb sign function.
    double sign(int joint, double velocity) const { return signs_[static_cast<std::size_t>(joint)](velocity); }

private:
    // The FCLj columns at (q, qd) into D (the nominal's columns left as they are).
    void write_load_columns(const double* q, const double* qd, Eigen::Ref<Eigen::MatrixXd> D) const;

    CoulombLoad law_;
    Eigen::VectorXd gravity_parameters_;  // the reference with its friction and offset entries zeroed
    std::vector<CoulombSign> signs_;
    std::vector<int> loaded_;
};

}  // namespace jacobid::robot
