// SPDX-License-Identifier: MIT
#pragma once
// One row of a modified Denavit-Hartenberg table (Khalil & Kleinfinger 1986): frame j is reached from
// its antecedent frame a(j) by Rot(x, alpha) Trans(x, d) Rot(z, theta) Trans(z, r), and joint j moves
// along/about z_j (theta += q for a revolute joint, r += q for a prismatic one). Because Rot(z) and
// Trans(z) commute, the whole row is a fixed transform followed by the joint motion about z, i.e. a
// ChainJoint with axis z.
#include <cmath>

#include "jacobid/robot/kinematic_chain.hpp"

namespace jacobid::robot {

struct MdhJoint {
    JointType type = JointType::Revolute;  // sigma 0: revolute, 1: prismatic
    int antecedent = -1;                   // -1: the base (Khalil's a(j) = 0), else 0-based joint index
    double alpha = 0.0, d = 0.0, theta = 0.0, r = 0.0;  // rad, m, rad, m (offsets at q = 0)
};

inline ChainJoint to_chain_joint(const MdhJoint& row) noexcept {
    const double ca = std::cos(row.alpha), sa = std::sin(row.alpha);
    const double ct = std::cos(row.theta), st = std::sin(row.theta);
    Eigen::Matrix3d rot_x;
    rot_x << 1.0, 0.0, 0.0, 0.0, ca, -sa, 0.0, sa, ca;
    Eigen::Matrix3d rot_z;
    rot_z << ct, -st, 0.0, st, ct, 0.0, 0.0, 0.0, 1.0;
    ChainJoint joint;
    joint.type = row.type;
    joint.antecedent = row.antecedent;
    joint.rotation = rot_x * rot_z;
    joint.position = Eigen::Vector3d(row.d, -sa * row.r, ca * row.r);
    joint.axis = Eigen::Vector3d::UnitZ();
    return joint;
}

}  // namespace jacobid::robot
