// SPDX-License-Identifier: MIT
#pragma once
// The independent reference: a serial chain as orocos-kdl segments (joint at the segment root with the
// chain joint's origin and axis, tip frame = the chain joint's fixed transform, so that root -> tip is
// Fixed * Motion(q) as in ours), inertias given as KDL wants them (mass, centre of mass, central inertia),
// torques from KDL's ChainIdSolver_RNE.
#include <kdl/chain.hpp>
#include <kdl/chainidsolver_recursive_newton_euler.hpp>

#include <array>
#include <vector>

#include "kdl_vector_copy.hpp"
#include "robot/serial_robot_model.hpp"

namespace jacobid::test {

// Standard inertial parameters of one link: XX XY XZ YY YZ ZZ MX MY MZ M (M > 0).
using LinkInertial = std::array<double, 10>;

inline KDL::Chain kdl_chain(const robot::SerialRobotConfig& config, const std::vector<LinkInertial>& links) {
    KDL::Chain chain;
    for (std::size_t j = 0; j < config.joints.size(); ++j) {
        const auto& joint = config.joints[j];
        const LinkInertial& p = links[j];
        const double m = p[9];
        const Eigen::Vector3d c = Eigen::Vector3d(p[6], p[7], p[8]) / m;
        // Standard parameters are about the link origin; KDL wants the central inertia.
        Eigen::Matrix3d io;
        io << p[0], p[1], p[2], p[1], p[3], p[4], p[2], p[4], p[5];
        const Eigen::Matrix3d ic = io - m * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
        const KDL::RigidBodyInertia inertia(m, KDL::Vector(c.x(), c.y(), c.z()),
                                            KDL::RotationalInertia(ic(0, 0), ic(1, 1), ic(2, 2), ic(0, 1), ic(0, 2), ic(1, 2)));
        const Eigen::Vector3d axis = joint.rotation * joint.axis;  // in the antecedent frame
        const KDL::Vector origin(joint.position.x(), joint.position.y(), joint.position.z());
        const auto& R = joint.rotation;
        const KDL::Frame tip(KDL::Rotation(R(0, 0), R(0, 1), R(0, 2), R(1, 0), R(1, 1), R(1, 2), R(2, 0), R(2, 1), R(2, 2)), origin);
        const KDL::Joint kdl_joint(origin, KDL::Vector(axis.x(), axis.y(), axis.z()),
                                   joint.type == robot::JointType::Revolute ? KDL::Joint::RotAxis : KDL::Joint::TransAxis);
        chain.addSegment(KDL::Segment(kdl_joint, tip, inertia));
    }
    return chain;
}

inline Eigen::VectorXd kdl_torques(const KDL::Chain& chain, const Eigen::Vector3d& gravity, const KDL::JntArray& q, const KDL::JntArray& qd,
                                   const KDL::JntArray& qdd) {
    KDL::ChainIdSolver_RNE solver(chain, KDL::Vector(gravity.x(), gravity.y(), gravity.z()));
    KDL::JntArray tau(chain.getNrOfJoints());
    const int status = solver.CartToJnt(q, qd, qdd, KDL::Wrenches(chain.getNrOfSegments(), KDL::Wrench::Zero()), tau);
    if (status < 0) throw std::runtime_error("KDL ChainIdSolver_RNE failed");
    return from_kdl(tau);
}

}  // namespace jacobid::test
