// SPDX-License-Identifier: MIT
#pragma once
// The joint table of a serial (or tree) robot, fixed capacity N joints. Every joint j carries the fixed
// transform from its antecedent's frame to its own frame at q_j = 0 (rotation + origin) and a unit axis
// in its own frame: a revolute joint rotates about the axis by q_j, a prismatic one translates along it.
// Modified DH rows (mdh_joint.hpp) and URDF joints (origin rpy/xyz + axis) both map onto this form, so
// one regressor serves both descriptions.
//
// Joints are added in topological order (antecedent before child); the table is validated once at
// construction time and then read-only, so the per-sample code needs no checks.
#include <Eigen/Core>
#include <Eigen/LU>  // determinant
#include <array>
#include <cmath>

namespace jacobid::robot {

enum class JointType { Revolute, Prismatic };

struct ChainJoint {
    JointType type = JointType::Revolute;
    int antecedent = -1;  // index of the antecedent joint (its link carries this joint), -1: the base
    Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  // joint frame in the antecedent frame at q = 0
    Eigen::Vector3d position = Eigen::Vector3d::Zero();      // joint frame origin in the antecedent frame
    Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();         // in the joint frame
};

enum class ChainError {
    Ok,
    TooManyJoints,  // more than the capacity N
    BadAntecedent,  // antecedent must be -1 (base) or an earlier joint
    ZeroAxis,       // the axis has no direction
    NotARotation,   // rotation is not orthonormal with determinant +1
    NonFinite,      // NaN or infinity in the transform or axis
};

inline const char* to_string(ChainError e) noexcept {
    switch (e) {
        case ChainError::Ok: return "ok";
        case ChainError::TooManyJoints: return "too many joints for the chain capacity";
        case ChainError::BadAntecedent: return "antecedent must be the base or an earlier joint";
        case ChainError::ZeroAxis: return "joint axis has zero length";
        case ChainError::NotARotation: return "rotation is not a proper orthonormal matrix";
        case ChainError::NonFinite: return "transform or axis is not finite";
    }
    return "unknown";
}

template <int N>
class KinematicChain {
public:
    static constexpr int kMaxJoints = N;

    // Appends a joint (its axis normalized); the table is unchanged on error.
    ChainError add(const ChainJoint& joint) noexcept {
        if (size_ >= N) return ChainError::TooManyJoints;
        if (joint.antecedent < -1 || joint.antecedent >= size_) return ChainError::BadAntecedent;
        if (!joint.rotation.allFinite() || !joint.position.allFinite() || !joint.axis.allFinite()) return ChainError::NonFinite;
        const double axis_norm = joint.axis.norm();
        if (!(axis_norm > 1e-12)) return ChainError::ZeroAxis;
        const double orthogonality = (joint.rotation.transpose() * joint.rotation - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
        if (orthogonality > 1e-9 || joint.rotation.determinant() < 0.0) return ChainError::NotARotation;
        joints_[static_cast<std::size_t>(size_)] = joint;
        joints_[static_cast<std::size_t>(size_)].axis /= axis_norm;
        ++size_;
        return ChainError::Ok;
    }

    int size() const noexcept { return size_; }
    const ChainJoint& joint(int j) const noexcept { return joints_[static_cast<std::size_t>(j)]; }

private:
    std::array<ChainJoint, N> joints_{};
    int size_ = 0;
};

}  // namespace jacobid::robot
