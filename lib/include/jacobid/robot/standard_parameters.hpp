// SPDX-License-Identifier: MIT
#pragma once
// Column layout of the standard dynamic parameters of an n-joint robot (Khalil's notation, link index
// appended: XX1 ... FC6). Per link j, in link j's frame, about its origin:
//   XXj XYj XZj YYj YZj ZZj (inertia tensor), MXj MYj MZj (first moments), Mj (mass),
// then per joint j: IAj (rotor inertia, optional), FVj (viscous), FCj (Coulomb), FOFFj (offset, optional).
// Optional kinds are skipped when switched off, so the columns are contiguous.
#include <array>

#include "jacobid/robot/coulomb_sign.hpp"

namespace jacobid::robot {

enum class ParameterKind { XX, XY, XZ, YY, YZ, ZZ, MX, MY, MZ, M, IA, FV, FC, FOFF };
constexpr int kKindsPerJoint = 14;
constexpr int kInertialKinds = 10;  // XX .. M

inline const char* kind_name(ParameterKind kind) noexcept {
    constexpr const char* kNames[kKindsPerJoint] = {"XX", "XY", "XZ", "YY", "YZ", "ZZ", "MX", "MY", "MZ", "M", "IA", "FV", "FC", "FOFF"};
    return kNames[static_cast<int>(kind)];
}

struct StandardParameterOptions {
    CoulombSign coulomb{};
    bool rotor_inertia = false;    // IAj: tau_j += IAj qdd_j
    bool friction_offset = false;  // FOFFj: constant torque
};

struct StandardParameterId {
    int joint = 0;  // 0-based
    ParameterKind kind = ParameterKind::XX;
};

template <int N>
class StandardParameterLayout {
public:
    static constexpr int kMaxParameters = kKindsPerJoint * N;

    StandardParameterLayout(int joints, const StandardParameterOptions& options) noexcept : joints_(joints) {
        per_joint_ = 0;
        for (int k = 0; k < kKindsPerJoint; ++k) {
            const auto kind = static_cast<ParameterKind>(k);
            const bool active = (kind != ParameterKind::IA || options.rotor_inertia) && (kind != ParameterKind::FOFF || options.friction_offset);
            offset_[static_cast<std::size_t>(k)] = active ? per_joint_++ : -1;
            if (active) kinds_[static_cast<std::size_t>(per_joint_ - 1)] = kind;
        }
    }

    int joints() const noexcept { return joints_; }
    int per_joint() const noexcept { return per_joint_; }
    int count() const noexcept { return per_joint_ * joints_; }
    // Column of (joint, kind), -1 when the kind is switched off.
    int column(int joint, ParameterKind kind) const noexcept {
        const int o = offset_[static_cast<std::size_t>(kind)];
        return o < 0 ? -1 : joint * per_joint_ + o;
    }
    StandardParameterId id(int column) const noexcept {
        return {column / per_joint_, kinds_[static_cast<std::size_t>(column % per_joint_)]};
    }

private:
    int joints_ = 0;
    int per_joint_ = 0;
    std::array<int, kKindsPerJoint> offset_{};
    std::array<ParameterKind, kKindsPerJoint> kinds_{};
};

}  // namespace jacobid::robot
