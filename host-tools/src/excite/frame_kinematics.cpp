// SPDX-License-Identifier: MIT
#include "excite/frame_kinematics.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <stdexcept>

namespace jacobid::excite {

FrameKinematics::FrameKinematics(std::vector<robot::ChainJoint> chain, int joint, FramePose offset, Eigen::Vector3d point)
    : chain_(std::move(chain)), offset_(offset), point_(point) {
    if (joint < 0 || joint >= static_cast<int>(chain_.size())) throw std::invalid_argument("FrameKinematics: the joint is not in the chain");
    for (auto& j : chain_) j.axis.normalize();
    for (int k = joint; k >= 0; k = chain_[static_cast<std::size_t>(k)].antecedent) {
        if (chain_[static_cast<std::size_t>(k)].antecedent >= k) throw std::invalid_argument("FrameKinematics: an antecedent must be an earlier joint");
        path_.push_back(k);
    }
    std::reverse(path_.begin(), path_.end());
}

namespace {

// Joint k's frame in the base frame, given its antecedent's (the joint's fixed transform, then its motion).
FramePose joint_frame(const FramePose& antecedent, const robot::ChainJoint& joint, double q) {
    FramePose fixed{antecedent.rotation * joint.rotation, antecedent.position + antecedent.rotation * joint.position};
    if (joint.type == robot::JointType::Revolute) {
        fixed.rotation = fixed.rotation * Eigen::AngleAxisd(q, joint.axis).toRotationMatrix();
    } else {
        fixed.position += fixed.rotation * (q * joint.axis);
    }
    return fixed;
}

}  // namespace

FramePose FrameKinematics::frame(const Eigen::Ref<const Eigen::VectorXd>& q) const {
    FramePose pose;
    for (const int k : path_) pose = joint_frame(pose, chain_[static_cast<std::size_t>(k)], q[k]);
    return {pose.rotation * offset_.rotation, pose.position + pose.rotation * offset_.position};
}

Eigen::Vector3d FrameKinematics::point(const Eigen::Ref<const Eigen::VectorXd>& q, Eigen::Matrix3Xd* jacobian) const {
    // The joints' axes and origins in the base frame along the path, kept for the Jacobian.
    Eigen::Matrix3Xd axes(3, path_.size()), origins(3, path_.size());
    FramePose pose;
    for (std::size_t i = 0; i < path_.size(); ++i) {
        const robot::ChainJoint& joint = chain_[static_cast<std::size_t>(path_[i])];
        pose = joint_frame(pose, joint, q[path_[i]]);
        // The motion is about (along) the axis, which it leaves unchanged: the axis after the motion is the axis.
        axes.col(static_cast<Eigen::Index>(i)) = pose.rotation * joint.axis;
        origins.col(static_cast<Eigen::Index>(i)) = pose.position;
    }
    const Eigen::Vector3d p = pose.position + pose.rotation * (offset_.position + offset_.rotation * point_);
    if (jacobian) {
        jacobian->setZero(3, joints());
        for (std::size_t i = 0; i < path_.size(); ++i) {
            const auto c = static_cast<Eigen::Index>(i);
            const bool revolute = chain_[static_cast<std::size_t>(path_[i])].type == robot::JointType::Revolute;
            jacobian->col(path_[i]) = revolute ? Eigen::Vector3d(axes.col(c).cross(p - origins.col(c))) : Eigen::Vector3d(axes.col(c));
        }
    }
    return p;
}

}  // namespace jacobid::excite
