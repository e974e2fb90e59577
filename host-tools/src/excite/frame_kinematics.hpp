// SPDX-License-Identifier: MIT
#pragma once
// Forward kinematics of one frame of a robot's kinematic chain (lib/include/jacobid/robot/kinematic_chain.hpp)
// and the translational Jacobian of a point fixed in that frame: what `jacobid excite --workspace-*` keeps
// inside a box (docs/excite.md, "Workspace box").
//
// Joint j's frame (the chain's convention) is its antecedent's frame, then the joint's fixed transform, then
// its motion (a rotation by q_j about the axis, or a translation by q_j along it): the frame moves with the
// link joint j drives. For MDH rows it is Khalil's frame j; for a URDF, the joint's child link frame. A frame
// fixed to that link (a URDF link behind fixed joints) is the joint frame followed by a constant offset.
#include <Eigen/Core>
#include <vector>

#include "jacobid/robot/kinematic_chain.hpp"

namespace jacobid::excite {

// A rigid transform: rotation and origin of a frame in a parent frame.
struct FramePose {
    Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
    Eigen::Vector3d position = Eigen::Vector3d::Zero();
};

class FrameKinematics {
public:
    // chain: the robot's joints in topological order; joint: 0-based index of the joint whose frame carries the
    // point; offset: the frame in that joint's frame (identity: the joint frame itself); point: in the frame
    // (m). std::invalid_argument for a joint outside the chain or a chain whose antecedents are not earlier joints.
    FrameKinematics(std::vector<robot::ChainJoint> chain, int joint, FramePose offset, Eigen::Vector3d point);

    int joints() const { return static_cast<int>(chain_.size()); }
    const Eigen::Vector3d& point_in_frame() const { return point_; }

    // The frame's pose in the base frame at q (joints() values).
    FramePose frame(const Eigen::Ref<const Eigen::VectorXd>& q) const;
    // The point in the base frame at q; when `jacobian` is not null, dp/dq (3 x joints(): z_k x (p - o_k) for
    // a revolute joint k between the base and the frame, z_k for a prismatic one, 0 for the other joints).
    Eigen::Vector3d point(const Eigen::Ref<const Eigen::VectorXd>& q, Eigen::Matrix3Xd* jacobian) const;

private:
    std::vector<robot::ChainJoint> chain_;
    std::vector<int> path_;  // the joints from the base to the frame's joint, base first
    FramePose offset_;
    Eigen::Vector3d point_;
};

}  // namespace jacobid::excite
