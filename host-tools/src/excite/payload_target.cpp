// SPDX-License-Identifier: MIT
#include "excite/payload_target.hpp"

#include <Eigen/Cholesky>
#include <fmt/core.h>

#include <cmath>
#include <limits>

#include "core/errors.hpp"
#include "payload/payload_inertia.hpp"
#include "robot/serial_robot_model.hpp"

namespace jacobid::excite {
namespace {

// The last link's ten standard parameters in the model's standard order (XX..M of payload_inertia.hpp).
std::vector<int> last_link_standard_columns(const robot::SerialRobotModel& model) {
    std::vector<int> columns;
    for (const std::string& kind : payload::standard_names()) {
        const int index = model.standard_index(fmt::format("{}{}", kind, model.joint_count()));
        if (index < 0) throw InputError(fmt::format("--payload: the model has no standard parameter {}{} to carry the payload", kind, model.joint_count()));
        columns.push_back(index);
    }
    return columns;
}

}  // namespace

PayloadTarget make_payload_target(const robot::RobotModel& model, double mass, const std::vector<double>& com) {
    const auto* serial = dynamic_cast<const robot::SerialRobotModel*>(&model);
    if (!serial) {
        throw InputError(fmt::format("--payload: model {} has no per-link standard parameters to carry a payload; describe the robot with model: mdh or urdf",
                                     model.model_name()));
    }
    if (!(mass > 0.0) || !std::isfinite(mass)) throw InputError(fmt::format("--payload-mass {}: expected the payload's expected mass, > 0 kg", mass));
    if (com.size() != 3 || !std::isfinite(com[0]) || !std::isfinite(com[1]) || !std::isfinite(com[2])) {
        throw InputError(fmt::format("--payload-com: {} values: expected x,y,z (m, finite) in the last link's frame", com.size()));
    }
    PayloadTarget t;
    t.mass = mass;
    t.com = Eigen::Vector3d(com[0], com[1], com[2]);
    t.link = model.joint_count();
    t.names = payload::standard_names();
    const std::vector<int> link = last_link_standard_columns(*serial);
    const Eigen::MatrixXd& regrouping = serial->base().regrouping;
    t.projection.resize(regrouping.rows(), 10);
    for (int k = 0; k < 10; ++k) t.projection.col(k) = regrouping.col(link[static_cast<std::size_t>(k)]);
    // A point mass: no inertia about its centre of mass.
    payload::Inertial point;
    point.mass = mass;
    point.com = t.com;
    t.prior = payload::to_standard(point, Eigen::Isometry3d::Identity());
    const double l = std::max(t.com.norm(), kPayloadMinSize);
    t.scales.resize(10);
    for (int k = 0; k < 10; ++k) {
        const double physical = k < 6 ? mass * l * l : k < 9 ? mass * l : mass;
        t.scales[k] = std::max(std::abs(t.prior[k]), physical / 10.0);
    }
    return t;
}

Eigen::VectorXd with_payload(const Eigen::VectorXd& base_values, const PayloadTarget& payload) { return base_values + payload.projection * payload.prior; }

Prediction predict_payload(const Eigen::MatrixXd& base_information, const PayloadTarget& payload) {
    return predict(payload.projection.transpose() * base_information * payload.projection, payload.scales);
}

Eigen::VectorXd predicted_inertial_std(const Eigen::MatrixXd& base_information, const PayloadTarget& payload) {
    Eigen::VectorXd out = Eigen::VectorXd::Constant(10, std::numeric_limits<double>::infinity());
    const Eigen::MatrixXd A = payload.projection.transpose() * base_information * payload.projection;
    if (!predict(A, payload.scales).identifiable) return out;
    // C = A^-1 after equilibration (the ten differ by orders of magnitude in their units).
    const Eigen::VectorXd d = A.diagonal().cwiseSqrt().cwiseInverse();
    const Eigen::MatrixXd C = d.asDiagonal() * (d.asDiagonal() * A * d.asDiagonal()).llt().solve(Eigen::MatrixXd::Identity(10, 10)) * d.asDiagonal();
    const payload::Standard10 prior = payload.prior;
    const Eigen::Matrix<double, 10, 10> J = payload::inertial_jacobian(prior, Eigen::Isometry3d::Identity());
    out = (J * C * J.transpose()).diagonal().cwiseMax(0.0).cwiseSqrt();
    return out;
}

}  // namespace jacobid::excite
