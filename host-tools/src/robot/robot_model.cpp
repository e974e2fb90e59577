// SPDX-License-Identifier: MIT
#include "robot/robot_model.hpp"

#include <Eigen/Cholesky>
#include <algorithm>

namespace jacobid::robot {

std::vector<int> RobotModel::coulomb_column_indices() const {
    std::vector<int> columns;
    // FCj: s_j(qd_j); FCLj (load-dependent Coulomb friction, load_friction_model.hpp): f_j(q) s_j(qd_j).
    for (const char* prefix : {"FC", "FCL"}) {
        for (int j = 0; j < joint_count(); ++j) {
            const int index = parameter_index(prefix + std::to_string(j + 1));
            if (index >= 0) columns.push_back(index);
        }
    }
    return columns;
}

int RobotModel::parameter_index(const std::string& name) const {
    const auto& names = parameter_names();
    const auto it = std::find(names.begin(), names.end(), name);
    return it == names.end() ? -1 : static_cast<int>(it - names.begin());
}

ForwardDynamics::ForwardDynamics(const RobotModel& model, Eigen::VectorXd parameters, ForwardDynamicsSolver solver)
    : model_(model),
      parameters_(std::move(parameters)),
      D_(model.joint_count(), model.parameter_count()),
      M_(model.joint_count(), model.joint_count()),
      zero_(Eigen::VectorXd::Zero(model.joint_count())),
      unit_(Eigen::VectorXd::Zero(model.joint_count())),
      bias_(model.joint_count()),
      rhs_(model.joint_count()),
      base_(model.joint_count()),
      llt_(model.joint_count()) {
    if (solver == ForwardDynamicsSolver::articulated_body) direct_ = model_.articulated_body(parameters_);
}

void ForwardDynamics::evaluate(const double* q, const double* qd, const double* qdd, Eigen::VectorXd& out) {
    if (model_.inverse_dynamics(q, qd, qdd, parameters_, out.data())) return;
    model_.regressor(q, qd, qdd, D_);
    out.noalias() = D_ * parameters_;
}

const Eigen::MatrixXd& ForwardDynamics::inertia(const double* q) {
    const Eigen::Index n = model_.joint_count();
    evaluate(q, zero_.data(), zero_.data(), base_);  // gravity, friction offsets: everything that does not depend on qdd
    for (Eigen::Index j = 0; j < n; ++j) {
        unit_.setZero();
        unit_[j] = 1.0;
        evaluate(q, zero_.data(), unit_.data(), rhs_);
        M_.col(j) = rhs_ - base_;
    }
    return M_;
}

bool ForwardDynamics::accelerations(const double* q, const double* qd, const double* tau, double* qdd) {
    if (direct_) return direct_->accelerations(q, qd, tau, qdd);
    const Eigen::Index n = model_.joint_count();
    inertia(q);
    evaluate(q, qd, zero_.data(), bias_);
    for (Eigen::Index j = 0; j < n; ++j) rhs_[j] = tau[j] - bias_[j];
    llt_.compute(M_);
    if (llt_.info() != Eigen::Success) return false;
    rhs_ = llt_.solve(rhs_);
    for (Eigen::Index j = 0; j < n; ++j) qdd[j] = rhs_[j];
    return true;
}

void ForwardDynamics::torques(const double* q, const double* qd, const double* qdd, double* tau) {
    evaluate(q, qd, qdd, rhs_);
    for (Eigen::Index j = 0; j < model_.joint_count(); ++j) tau[j] = rhs_[j];
}

}  // namespace jacobid::robot
