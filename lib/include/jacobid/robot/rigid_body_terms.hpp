// SPDX-License-Identifier: MIT
#pragma once
// The rigid-body terms an external-torque estimator needs from an identified model (docs/method.md,
// "External torque and contact detection"), each from the Newton-Euler inverse dynamics of
// rnea_regressor.hpp on the identified standard parameters with the friction columns set to 0:
//   g(q)            = ID(q, 0, 0)                with gravity,
//   p = M(q) qd     = ID(q, 0, qd)               without gravity (rotor inertia included),
//   C(q, qd) qd     = ID(q, qd, 0)               without gravity,
//   C^T qd          = Mdot qd - C qd             (Mdot = C + C^T, the skew-symmetry of Mdot - 2C),
//   Mdot qd         = [M(q + h qd) - M(q - h qd)] qd / (2h),
// the last a central difference along the motion: one Newton-Euler pass per side, exact to O((h |qd|)^2)
// (h |qd| = 1e-5 rad: 1e-10 relative), where the analytic route (the derivative of the recursion) would
// double the code. Six O(n) passes per sample in all; fixed-size, allocation-free, no exceptions.
#include <Eigen/Core>
#include <cmath>

#include "jacobid/robot/rnea_regressor.hpp"

namespace jacobid::robot {

template <int N>
class RigidBodyTerms {
public:
    using Regressor = RneaRegressor<N>;
    using Joints = typename Regressor::Joints;
    using Parameters = typename Regressor::Parameters;

    // `regressor` carries the chain, the gravity and the parameter layout; X its standard parameters (the
    // friction columns FV, FC, FOFF are ignored here: joint_friction.hpp models them).
    RigidBodyTerms(const Regressor& regressor, const Parameters& X) noexcept
        : with_gravity_(regressor), without_gravity_(regressor.chain(), Eigen::Vector3d::Zero(), regressor.options()), X_(X) {
        const auto& layout = regressor.layout();
        for (int j = 0; j < regressor.joint_count(); ++j) {
            for (ParameterKind kind : {ParameterKind::FV, ParameterKind::FC, ParameterKind::FOFF}) {
                const int c = layout.column(j, kind);
                if (c >= 0) X_[c] = 0.0;
            }
        }
    }

    int joint_count() const noexcept { return with_gravity_.joint_count(); }
    const Regressor& regressor() const noexcept { return with_gravity_; }

    RegressorStatus gravity(const Joints& q, Joints& g) const noexcept {
        return with_gravity_.inverse_dynamics(q, Joints::Zero(), Joints::Zero(), X_, g);
    }
    RegressorStatus momentum(const Joints& q, const Joints& qd, Joints& p) const noexcept {
        return without_gravity_.inverse_dynamics(q, Joints::Zero(), qd, X_, p);
    }
    // Rigid-body inverse dynamics M qdd + C qd + g, without friction.
    RegressorStatus inverse_dynamics(const Joints& q, const Joints& qd, const Joints& qdd, Joints& tau) const noexcept {
        return with_gravity_.inverse_dynamics(q, qd, qdd, X_, tau);
    }
    // C(q, qd)^T qd (see the header comment).
    RegressorStatus coriolis_transpose(const Joints& q, const Joints& qd, Joints& out) const noexcept {
        const int n = joint_count();
        Joints c_qd;
        const RegressorStatus s = without_gravity_.inverse_dynamics(q, qd, Joints::Zero(), X_, c_qd);
        if (s != RegressorStatus::Ok) return s;
        double speed = 0.0;
        for (int j = 0; j < n; ++j) speed = std::max(speed, std::abs(qd[j]));
        if (!(speed > 0.0)) {
            out.setZero();
            return RegressorStatus::Ok;
        }
        const double h = kStep / speed;
        Joints ahead, behind;
        without_gravity_.inverse_dynamics(q + h * qd, Joints::Zero(), qd, X_, ahead);
        without_gravity_.inverse_dynamics(q - h * qd, Joints::Zero(), qd, X_, behind);
        out = (ahead - behind) / (2.0 * h) - c_qd;
        if (n < N) out.tail(N - n).setZero();
        return RegressorStatus::Ok;
    }

private:
    static constexpr double kStep = 1e-5;  // rad: the largest joint's displacement of the central difference
    Regressor with_gravity_;
    Regressor without_gravity_;
    Parameters X_;
};

}  // namespace jacobid::robot
