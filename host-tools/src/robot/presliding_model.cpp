// SPDX-License-Identifier: MIT
#include "robot/presliding_model.hpp"

#include <fmt/core.h>

#include <stdexcept>
#include <utility>

#include "jacobid/robot/presliding_friction.hpp"
#include "robot/load_friction_model.hpp"

namespace jacobid::robot {

PreslidingModel::PreslidingModel(std::unique_ptr<RobotModel> nominal, PreslidingSettings settings)
    : ModelExtension(std::move(nominal)), settings_(std::move(settings)) {
    add_presliding_columns();
}

PreslidingModel::PreslidingModel(const RobotModel& nominal, PreslidingSettings settings) : ModelExtension(nominal), settings_(std::move(settings)) {
    add_presliding_columns();
}

void PreslidingModel::add_presliding_columns() {
    const auto joints = static_cast<std::size_t>(joint_count());
    if (settings_.displacement.size() != joints) {
        throw std::invalid_argument(fmt::format("presliding friction: {} displacements for {} joints", settings_.displacement.size(), joints));
    }
    for (const double x : settings_.displacement) {
        if (!(x > 0.0)) throw std::invalid_argument(fmt::format("presliding friction: displacement {} rad must be > 0", x));
    }
    for (std::size_t j = 0; j < joints; ++j) append_parameter(fmt::format("FD{}", j + 1));
}

void PreslidingModel::regressor(const double* q, const double* qd, const double* qdd, Eigen::Ref<Eigen::MatrixXd> D) const {
    const int p = nominal_parameter_count();
    nominal().regressor(q, qd, qdd, D.leftCols(p));
    D.rightCols(D.cols() - p).setZero();
}

void PreslidingModel::coulomb_columns(const double* q, const double* qd, const double* qdd, Eigen::Ref<Eigen::MatrixXd> D) const {
    nominal().coulomb_columns(q, qd, qdd, D.leftCols(nominal_parameter_count()));
}

void PreslidingModel::integrate_history(const std::vector<const std::vector<double>*>& q, std::vector<double>& state) const {
    const std::size_t joints = q.size();
    const std::size_t n = joints ? q.front()->size() : 0;
    state.assign(n * joints, 0.0);
    for (std::size_t j = 0; j < joints; ++j) {
        const std::vector<double> s = presliding_states(*q[j], settings_.displacement[j], settings_.play_width,
                                                       j < settings_.initial_state.size() ? settings_.initial_state[j] : 0.0);
        for (std::size_t k = 0; k < n; ++k) state[k * joints + j] = s[k];
    }
}

void PreslidingModel::history_columns(const double* state, Eigen::Ref<Eigen::MatrixXd> D) const {
    const int p = nominal_parameter_count();
    for (int j = 0; j < joint_count(); ++j) D(j, p + j) = state[j];
}

const RobotModel& rigid_body(const RobotModel& model) {
    const auto* presliding = dynamic_cast<const PreslidingModel*>(&model);
    const RobotModel& inner = presliding ? presliding->nominal() : model;
    const auto* loaded = dynamic_cast<const LoadFrictionModel*>(&inner);
    return loaded ? loaded->nominal() : inner;
}

std::vector<double> presliding_states(const std::vector<double>& q, double displacement, double play_width, double initial_state) {
    PreslidingFriction friction(displacement, 0.5 * play_width, initial_state);
    std::vector<double> s(q.size());
    for (std::size_t k = 0; k < q.size(); ++k) s[k] = friction.step(q[k]);
    return s;
}

}  // namespace jacobid::robot
