// SPDX-License-Identifier: MIT
#include "identify/validation/static_validation.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>

#include "core/errors.hpp"

namespace jacobid::identify {

bool is_static(const LogColumns& log, double min_joint_motion) {
    for (const auto* q : log.q) {
        if (q->empty()) continue;
        const auto [lo, hi] = std::minmax_element(q->begin(), q->end());
        if (*hi - *lo > min_joint_motion) return false;
    }
    return true;
}

StaticValidationResult validate_static(const robot::RobotModel& model, const LogColumns& log, const Eigen::VectorXd& x_in) {
    const Eigen::VectorXd x = x_in.unaryExpr([](double v) { return std::isnan(v) ? 0.0 : v; });
    const auto joints = static_cast<std::size_t>(model.joint_count());
    const std::size_t n = log.samples();
    if (n == 0) throw InputError(fmt::format("{}: no samples to validate on", log.source));
    StaticValidationResult r;
    r.source = log.source;
    r.samples = n;
    r.pose.assign(joints, 0.0);
    r.joints.resize(joints);
    for (std::size_t j = 0; j < joints; ++j) {
        double q = 0.0, tau = 0.0;
        for (std::size_t k = 0; k < n; ++k) {
            q += (*log.q[j])[k];
            tau += (*log.tau[j])[k];
        }
        r.pose[j] = q / static_cast<double>(n);
        r.joints[j].measured = tau / static_cast<double>(n);
        double var = 0.0;
        for (std::size_t k = 0; k < n; ++k) var += std::pow((*log.tau[j])[k] - r.joints[j].measured, 2);
        r.joints[j].measured_std = n > 1 ? std::sqrt(var / static_cast<double>(n - 1)) : 0.0;
    }
    const std::vector<double> zero(joints, 0.0);
    Eigen::MatrixXd D(model.joint_count(), model.parameter_count());
    model.regressor(r.pose.data(), zero.data(), zero.data(), D);
    const Eigen::VectorXd predicted = D * x;
    double e2 = 0.0, y2 = 0.0;
    for (std::size_t j = 0; j < joints; ++j) {
        auto& e = r.joints[j];
        e.predicted = predicted[static_cast<Eigen::Index>(j)];
        e.error = e.measured - e.predicted;
        const int fc = model.parameter_index(fmt::format("FC{}", j + 1));
        e.coulomb = fc >= 0 ? std::abs(x[fc]) : NAN;
        e.within_friction = fc >= 0 && std::abs(e.error) <= e.coulomb;
        e2 += e.error * e.error;
        y2 += e.measured * e.measured;
    }
    r.relative_error = y2 > 0.0 ? std::sqrt(e2 / y2) : 0.0;
    return r;
}

}  // namespace jacobid::identify
