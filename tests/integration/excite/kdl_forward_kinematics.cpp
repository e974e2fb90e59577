// SPDX-License-Identifier: MIT
#include "kdl_forward_kinematics.hpp"

#include <kdl/chain.hpp>
#include <kdl/chainfksolverpos_recursive.hpp>

#include <stdexcept>

namespace jacobid::test {

std::array<double, 12> kdl_frame_pose(const std::vector<PlainJoint>& chain, const std::vector<double>& q, int frame) {
    // Segment j: the joint at the segment root with the joint's origin and its axis in the antecedent frame,
    // tip = the joint's fixed transform, so that root -> tip is Fixed * Motion(q) as in the chain.
    KDL::Chain kdl;
    for (const PlainJoint& j : chain) {
        const auto& R = j.rotation;
        const KDL::Rotation rotation(R[0], R[1], R[2], R[3], R[4], R[5], R[6], R[7], R[8]);
        const KDL::Vector origin(j.position[0], j.position[1], j.position[2]);
        const KDL::Vector axis = rotation * KDL::Vector(j.axis[0], j.axis[1], j.axis[2]);
        kdl.addSegment(KDL::Segment(KDL::Joint(origin, axis, j.revolute ? KDL::Joint::RotAxis : KDL::Joint::TransAxis), KDL::Frame(rotation, origin)));
    }
    KDL::JntArray joints(kdl.getNrOfJoints());
    for (unsigned i = 0; i < joints.rows(); ++i) joints(i) = q.at(i);
    KDL::ChainFkSolverPos_recursive solver(kdl);
    KDL::Frame pose;
    if (solver.JntToCart(joints, pose, frame) < 0) throw std::runtime_error("KDL ChainFkSolverPos_recursive failed");
    std::array<double, 12> out{};
    for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) out[static_cast<std::size_t>(3 * r + c)] = pose.M(r, c);
        out[static_cast<std::size_t>(9 + r)] = pose.p(r);
    }
    return out;
}

}  // namespace jacobid::test
