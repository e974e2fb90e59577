// SPDX-License-Identifier: MIT
#pragma once
// A URDF (through urdfdom) as a kinematic chain: every revolute, continuous or prismatic joint becomes a
// ChainJoint whose fixed transform is the joint origin (composed with the origins of any fixed joints
// between it and its moving antecedent) and whose axis is the URDF axis; the child link frame is the joint
// frame. Link inertials (mass, centre of mass, central inertia in the inertial frame) become the standard
// parameters of the moving body that carries them (fixed links are merged), about the link frame origin:
//   M = m, MS = m c, I_O = R I_G R^T + m (|c|^2 E - c c^T);
// <dynamics damping friction> become FVj and FCj. Errors: InputError "file: element <joint name='x'>: ...".
#include <string>
#include <utility>
#include <vector>

#include "jacobid/robot/kinematic_chain.hpp"

namespace jacobid::robot {

// A URDF link's frame: the moving body that carries it (index into joints, -1: fixed to the base) and the
// link frame in that body's frame (the origins of the fixed joints between them; identity for the body link).
struct UrdfLinkFrame {
    std::string name;
    int body = -1;
    Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
    Eigen::Vector3d position = Eigen::Vector3d::Zero();
};

struct UrdfChain {
    std::vector<ChainJoint> joints;   // moving joints in topological order
    std::vector<std::string> names;   // URDF joint names
    std::vector<std::pair<double, double>> limits;  // [lower, upper]; continuous joints: [-pi, pi]
    std::vector<bool> limits_given;                  // the URDF's <limit> (false: continuous, [-pi, pi]; any other joint must have lower < upper)
    std::vector<std::pair<std::string, double>> standard_parameters;  // XX1 ... M_n, FVj, FCj from the file
    // Per moving joint: its child link (whose frame is the body frame of the standard parameters), and the
    // links fixed to that body whose <inertial> was merged into the body's standard parameters.
    std::vector<std::string> body_links;
    std::vector<std::vector<std::string>> merged_links;
    std::vector<UrdfLinkFrame> links;  // every link, in the order visited from the root
};

// xml: the URDF text; source names it in error messages (the file path, or e.g. "<fuzz>").
UrdfChain parse_urdf_chain(const std::string& xml, const std::string& source);
UrdfChain load_urdf_chain(const std::string& path);

}  // namespace jacobid::robot
