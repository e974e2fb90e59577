// SPDX-License-Identifier: MIT
#include "identify/friction/presliding_initial_state.hpp"

#include <algorithm>
#include <cmath>

namespace jacobid::identify {

std::vector<double> observe_initial_presliding_state(const robot::PreslidingModel& model, const LogColumns& log, const Eigen::VectorXd& x,
                                                     double window) {
    const int joints = model.joint_count();
    const auto nj = static_cast<std::size_t>(joints);
    std::vector<double> s0(nj, 0.0);
    const std::size_t n = log.samples();
    const std::size_t m = std::min(n, static_cast<std::size_t>(std::ceil(window / log.sample_period)) + 1);
    if (m == 0) return s0;
    // Held torque minus the model's torque at rest (gravity, offset; the state's columns left at 0).
    Eigen::MatrixXd D(joints, model.parameter_count());
    std::vector<double> q(nj), zero(nj, 0.0);
    Eigen::VectorXd held = Eigen::VectorXd::Zero(joints);
    for (std::size_t k = 0; k < m; ++k) {
        for (std::size_t j = 0; j < nj; ++j) q[j] = (*log.q[j])[k];
        model.regressor(q.data(), zero.data(), zero.data(), D);
        const Eigen::VectorXd rest = D * x;
        for (std::size_t j = 0; j < nj; ++j) held[static_cast<Eigen::Index>(j)] += (*log.tau[j])[k] - rest[static_cast<Eigen::Index>(j)];
    }
    held /= static_cast<double>(m);
    for (std::size_t j = 0; j < nj; ++j) {
        const auto [lo, hi] = std::minmax_element(log.q[j]->begin(), log.q[j]->begin() + static_cast<std::ptrdiff_t>(m));
        const bool at_rest = *hi - *lo <= model.settings().play_width;
        const double level = x[model.first_presliding_column() + static_cast<Eigen::Index>(j)];
        if (at_rest && std::isfinite(level) && level > 0.0) s0[j] = std::clamp(held[static_cast<Eigen::Index>(j)] / level, -1.0, 1.0);
    }
    return s0;
}

const robot::RobotModel& with_observed_initial_state(const robot::RobotModel& model, const LogColumns& log, const Eigen::VectorXd& x,
                                                     std::unique_ptr<robot::RobotModel>& holder) {
    const auto* presliding = dynamic_cast<const robot::PreslidingModel*>(&model);
    if (!presliding) return model;
    robot::PreslidingSettings settings = presliding->settings();
    settings.initial_state = observe_initial_presliding_state(*presliding, log, x);
    holder = std::make_unique<robot::PreslidingModel>(presliding->nominal(), settings);
    return *holder;
}

}  // namespace jacobid::identify
