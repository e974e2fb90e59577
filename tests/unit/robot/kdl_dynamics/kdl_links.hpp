// SPDX-License-Identifier: MIT
#pragma once
// A serial model's chain and standard parameter vector as the plain links of KdlDynamics (compiled on our
// side of the boundary: only doubles go into kdl_dynamics.cpp).
#include <vector>

#include "kdl_dynamics.hpp"
#include "robot/serial_robot_model.hpp"

namespace jacobid::test {

// standard: in the model's standard order (SerialRobotModel::standard_names, robot::standard_values).
inline std::vector<KdlLink> kdl_links(const robot::SerialRobotConfig& config, const Eigen::VectorXd& standard) {
    const int n = static_cast<int>(config.joints.size());
    const robot::StandardParameterLayout<robot::kMaxSerialJoints> layout(n, config.options);
    std::vector<KdlLink> links;
    for (int j = 0; j < n; ++j) {
        const robot::ChainJoint& joint = config.joints[static_cast<std::size_t>(j)];
        KdlLink link;
        link.prismatic = joint.type == robot::JointType::Prismatic;
        for (int r = 0; r < 3; ++r) {
            for (int c = 0; c < 3; ++c) link.rotation[static_cast<std::size_t>(3 * r + c)] = joint.rotation(r, c);
            link.position[static_cast<std::size_t>(r)] = joint.position[r];
            link.axis[static_cast<std::size_t>(r)] = joint.axis[r];
        }
        for (int k = 0; k < robot::kInertialKinds; ++k) {
            link.inertial[static_cast<std::size_t>(k)] = standard[layout.column(j, static_cast<robot::ParameterKind>(k))];
        }
        const int ia = layout.column(j, robot::ParameterKind::IA);
        link.rotor_inertia = ia >= 0 ? standard[ia] : 0.0;
        links.push_back(link);
    }
    return links;
}

inline std::array<double, 3> kdl_gravity(const robot::SerialRobotConfig& config) {
    return {config.gravity.x(), config.gravity.y(), config.gravity.z()};
}

}  // namespace jacobid::test
