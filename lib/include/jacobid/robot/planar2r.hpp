// SPDX-License-Identifier: MIT
#pragma once
// The 2R planar robot moving in a horizontal plane (no gravity), modified DH with d2 = L1
// (docs/method.md, "The planar 2R robot"). Base parameters, in the paper's order:
//   ZZ1R = ZZ1 + Ia1 + M2 L1^2, FV1, FC1, ZZ2, MX2, MY2, FV2, FC2
// plus optional columns: a constant friction offset per joint (FOFF1, FOFF2, e.g. an unbalanced torque
// sensor) and the rotor inertia of joint 2 (IA2, which acts on joint 2 only, so it does not regroup into
// ZZ2). Optional parameters are inserted next to their joint's parameters.
//
// Model built once (configuration -> column layout), then regressor() is a pure, allocation-free function.
#include <array>
#include <cmath>

#include "jacobid/robot/coulomb_sign.hpp"
#include "jacobid/robot/regressor.hpp"

namespace jacobid::robot {

struct Planar2RConfig {
    double L1 = 0.5;           // length of link 1 in m (d2 of the MDH table)
    CoulombSign coulomb{};     // sign(qd) or its smoothed version, for both joints (Planar2R::set_coulomb: per joint)
    bool friction_offset = false;  // adds FOFF1, FOFF2
    bool rotor_inertia = false;    // adds IA2
};

class Planar2R {
public:
    static constexpr int kJoints = 2;
    static constexpr int kMaxParameters = 11;
    using Regressor = RegressorMatrix<kJoints, kMaxParameters>;
    using Joints = JointVector<kJoints>;

    // Every parameter the model knows, in output order; inactive ones are skipped.
    enum class Parameter { ZZ1R, FV1, FC1, FOFF1, ZZ2, MX2, MY2, IA2, FV2, FC2, FOFF2 };

    explicit Planar2R(const Planar2RConfig& config = {}) noexcept : config_(config) {
        int next = 0;
        for (int p = 0; p < kMaxParameters; ++p) {
            const auto parameter = static_cast<Parameter>(p);
            const bool active = (parameter != Parameter::FOFF1 && parameter != Parameter::FOFF2 && parameter != Parameter::IA2) ||
                                ((parameter == Parameter::FOFF1 || parameter == Parameter::FOFF2) && config.friction_offset) ||
                                (parameter == Parameter::IA2 && config.rotor_inertia);
            column_[p] = active ? next++ : -1;
            if (active) active_[next - 1] = parameter;
        }
        parameter_count_ = next;
        coulomb_.fill(config.coulomb);
    }

    // Joint `joint`'s (0 or 1) Coulomb sign function, config.coulomb by default: the smoothing can differ per joint.
    void set_coulomb(int joint, const CoulombSign& sign) noexcept {
        if (joint >= 0 && joint < kJoints) coulomb_[static_cast<std::size_t>(joint)] = sign;
    }
    const CoulombSign& coulomb(int joint) const noexcept { return coulomb_[static_cast<std::size_t>(joint)]; }

    const Planar2RConfig& config() const noexcept { return config_; }
    int parameter_count() const noexcept { return parameter_count_; }
    // Column of `parameter` in D, or -1 when the configuration does not use it.
    int column(Parameter parameter) const noexcept { return column_[static_cast<int>(parameter)]; }
    Parameter parameter_at(int column) const noexcept { return active_[column]; }

    static const char* name(Parameter parameter) noexcept {
        constexpr const char* kNames[kMaxParameters] = {"ZZ1R", "FV1", "FC1", "FOFF1", "ZZ2", "MX2", "MY2", "IA2", "FV2", "FC2", "FOFF2"};
        return kNames[static_cast<int>(parameter)];
    }
    const char* parameter_name(int column) const noexcept { return name(active_[column]); }

    // Fills the first parameter_count() columns of D; the remaining columns are left untouched.
    void regressor(const Joints& q, const Joints& qd, const Joints& qdd, Regressor& D) const noexcept {
        const double l1 = config_.L1;
        const double c2 = std::cos(q[1]);
        const double s2 = std::sin(q[1]);
        const double qdd12 = qdd[0] + qdd[1];
        // Joint 1 sees link 2's first moment through the acceleration of joint 2's axis (2qdd1 + qdd2 term)
        // and the Coriolis/centrifugal terms; joint 2 only through link 1's motion (qdd1, qd1^2).
        const double a1 = 2.0 * qdd[0] + qdd[1];
        const double v1 = 2.0 * qd[0] * qd[1] + qd[1] * qd[1];
        const double qd1_sq = qd[0] * qd[0];
        set(D, Parameter::ZZ1R, qdd[0], 0.0);
        set(D, Parameter::FV1, qd[0], 0.0);
        set(D, Parameter::FC1, coulomb_[0](qd[0]), 0.0);
        set(D, Parameter::FOFF1, 1.0, 0.0);
        set(D, Parameter::ZZ2, qdd12, qdd12);
        set(D, Parameter::MX2, l1 * (a1 * c2 - v1 * s2), l1 * (qdd[0] * c2 + qd1_sq * s2));
        set(D, Parameter::MY2, -l1 * (a1 * s2 + v1 * c2), l1 * (qd1_sq * c2 - qdd[0] * s2));
        set(D, Parameter::IA2, 0.0, qdd[1]);
        set(D, Parameter::FV2, 0.0, qd[1]);
        set(D, Parameter::FC2, 0.0, coulomb_[1](qd[1]));
        set(D, Parameter::FOFF2, 0.0, 1.0);
    }

private:
    void set(Regressor& D, Parameter parameter, double joint1, double joint2) const noexcept {
        const int c = column_[static_cast<int>(parameter)];
        if (c < 0) return;
        D(0, c) = joint1;
        D(1, c) = joint2;
    }

    Planar2RConfig config_;
    std::array<CoulombSign, kJoints> coulomb_{};
    std::array<int, kMaxParameters> column_{};
    std::array<Parameter, kMaxParameters> active_{};
    int parameter_count_ = 0;
};

}  // namespace jacobid::robot
