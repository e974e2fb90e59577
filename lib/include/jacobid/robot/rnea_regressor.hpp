// SPDX-License-Identifier: MIT
#pragma once
// Regressor of the standard parameters (standard_parameters.hpp) of a serial or tree robot by the
// recursive Newton-Euler algorithm in linear form (Khalil & Dombre, ch. 9 and 12; Atkeson et al. 1986):
//   forward:  angular velocity w_j, angular acceleration wd_j and linear acceleration vd_j of every link
//             frame origin, in the link's own frame, with gravity entering as vd_base = -g;
//   per link: the wrench at the link origin is linear in its ten inertial parameters,
//             f_j = M vd + (S(wd) + S(w)^2) MS,  n_j = I wd + w x (I w) - S(vd) MS,
//             i.e. a 6x10 matrix K_j;
//   backward: joint i carries the wrenches of all links j it supports; its torque is the projection of
//             K_j onto axis i, written in frame j (w = R_0j^T (z_i x (o_j - o_i)), u = R_0j^T z_i for a
//             revolute joint, w = R_0j^T z_i for a prismatic one).
// Friction and rotor inertia act on their own joint only. Everything is fixed-size: no allocation.
//
// inverse_dynamics() is the same model evaluated for one parameter vector (tau = W X) by the ordinary
// backward recursion of the link wrenches, O(n) instead of the regressor's O(n^2) projections: the
// simulator's forward dynamics calls it n + 2 times per acceleration.
#include <Eigen/Core>
#include <Eigen/Geometry>  // cross products
#include <array>
#include <cmath>

#include "jacobid/robot/kinematic_chain.hpp"
#include "jacobid/robot/regressor.hpp"
#include "jacobid/robot/standard_parameters.hpp"

namespace jacobid::robot {

enum class RegressorStatus {
    Ok,
    NonFiniteInput,  // NaN or infinity in q, qd or qdd
};

template <int N>
class RneaRegressor {
public:
    static constexpr int kMaxJoints = N;
    static constexpr int kMaxParameters = kKindsPerJoint * N;
    using Regressor = RegressorMatrix<N, kMaxParameters>;
    using Joints = JointVector<N>;
    using Layout = StandardParameterLayout<N>;

    // gravity: acceleration of gravity in the base frame, e.g. (0, 0, -9.81).
    RneaRegressor(const KinematicChain<N>& chain, const Eigen::Vector3d& gravity, const StandardParameterOptions& options) noexcept
        : chain_(chain), gravity_(gravity), options_(options), layout_(chain.size(), options) {
        coulomb_.fill(options.coulomb);
    }

    // Joint `joint`'s Coulomb sign function (default: options.coulomb for every joint). Real drives differ
    // in how sharply friction reverses, so the smoothing can be chosen per joint (docs/method.md, "Pitfalls").
    void set_coulomb(int joint, const CoulombSign& sign) noexcept {
        if (joint >= 0 && joint < N) coulomb_[static_cast<std::size_t>(joint)] = sign;
    }
    const CoulombSign& coulomb(int joint) const noexcept { return coulomb_[static_cast<std::size_t>(joint)]; }

    int joint_count() const noexcept { return chain_.size(); }
    int parameter_count() const noexcept { return layout_.count(); }
    const Layout& layout() const noexcept { return layout_; }
    const KinematicChain<N>& chain() const noexcept { return chain_; }
    const Eigen::Vector3d& gravity() const noexcept { return gravity_; }
    const StandardParameterOptions& options() const noexcept { return options_; }

    // Fills rows [0, joint_count()) and columns [0, parameter_count()) of D; the rest is untouched.
    RegressorStatus regressor(const Joints& q, const Joints& qd, const Joints& qdd, Regressor& D) const noexcept {
        const int n = chain_.size();
        for (int j = 0; j < n; ++j) {
            if (!std::isfinite(q[j]) || !std::isfinite(qd[j]) || !std::isfinite(qdd[j])) return RegressorStatus::NonFiniteInput;
        }
        D.topLeftCorner(n, layout_.count()).setZero();
        std::array<LinkState, N> links;
        forward(q, qd, qdd, links);
        for (int j = 0; j < n; ++j) {
            const LinkState& link = links[static_cast<std::size_t>(j)];
            const Eigen::Matrix<double, 6, kInertialKinds> K = wrench_matrix(link);
            const int first = layout_.column(j, ParameterKind::XX);
            // Every joint on the path from link j to the base carries link j's wrench.
            for (int i = j; i >= 0; i = chain_.joint(i).antecedent) {
                const LinkState& carrier = links[static_cast<std::size_t>(i)];
                const Eigen::Vector3d z_in_j = link.R0.transpose() * carrier.z0;
                Eigen::Matrix<double, 1, 6> e;
                if (chain_.joint(i).type == JointType::Revolute) {
                    e.template head<3>() = link.R0.transpose() * carrier.z0.cross(link.o0 - carrier.o0);
                    e.template tail<3>() = z_in_j;
                } else {
                    e.template head<3>() = z_in_j;
                    e.template tail<3>().setZero();
                }
                D.row(i).template segment<kInertialKinds>(first).noalias() = e * K;
            }
            const int ia = layout_.column(j, ParameterKind::IA);
            if (ia >= 0) D(j, ia) = qdd[j];
            D(j, layout_.column(j, ParameterKind::FV)) = qd[j];
            D(j, layout_.column(j, ParameterKind::FC)) = coulomb(j)(qd[j]);
            const int offset = layout_.column(j, ParameterKind::FOFF);
            if (offset >= 0) D(j, offset) = 1.0;
        }
        return RegressorStatus::Ok;
    }

    using Parameters = Eigen::Matrix<double, kMaxParameters, 1>;

    // tau = W(q, qd, qdd) X for standard parameters X (the first parameter_count() entries are used).
    RegressorStatus inverse_dynamics(const Joints& q, const Joints& qd, const Joints& qdd, const Parameters& X, Joints& tau) const noexcept {
        const int n = chain_.size();
        for (int j = 0; j < n; ++j) {
            if (!std::isfinite(q[j]) || !std::isfinite(qd[j]) || !std::isfinite(qdd[j])) return RegressorStatus::NonFiniteInput;
        }
        std::array<LinkState, N> links;
        forward(q, qd, qdd, links);
        std::array<Eigen::Matrix<double, 6, 1>, N> wrench;  // [f; n] at each link origin, in its frame, of the link and its descendants
        for (int j = 0; j < n; ++j) {
            wrench[static_cast<std::size_t>(j)] =
                wrench_matrix(links[static_cast<std::size_t>(j)]) * X.template segment<kInertialKinds>(layout_.column(j, ParameterKind::XX));
        }
        for (int j = n - 1; j >= 0; --j) {
            const LinkState& link = links[static_cast<std::size_t>(j)];
            const ChainJoint& joint = chain_.joint(j);
            const Eigen::Matrix<double, 6, 1>& w = wrench[static_cast<std::size_t>(j)];
            tau[j] = joint.type == JointType::Revolute ? joint.axis.dot(w.template tail<3>()) : joint.axis.dot(w.template head<3>());
            const int ia = layout_.column(j, ParameterKind::IA);
            if (ia >= 0) tau[j] += X[ia] * qdd[j];
            tau[j] += X[layout_.column(j, ParameterKind::FV)] * qd[j] + X[layout_.column(j, ParameterKind::FC)] * coulomb(j)(qd[j]);
            const int offset = layout_.column(j, ParameterKind::FOFF);
            if (offset >= 0) tau[j] += X[offset];
            if (joint.antecedent >= 0) {
                const Eigen::Vector3d f = link.R * w.template head<3>();
                auto& parent = wrench[static_cast<std::size_t>(joint.antecedent)];
                parent.template head<3>() += f;
                parent.template tail<3>() += link.R * w.template tail<3>() + link.p.cross(f);
            }
        }
        return RegressorStatus::Ok;
    }

    // The pieces of the regressor, public for its adjoint (rnea_regressor_adjoint.hpp), which differentiates
    // the same forward pass and wrench matrices rather than a copy of them.
    // Kinematics of one link frame: w, wd, vd in the link frame; orientation, origin and joint axis in the base frame.
    struct LinkState {
        Eigen::Matrix3d R;  // link frame in the antecedent frame, at q
        Eigen::Vector3d p;  // link origin in the antecedent frame, at q
        Eigen::Vector3d w, wd, vd;
        Eigen::Matrix3d R0;
        Eigen::Vector3d o0, z0;
    };

    static Eigen::Matrix3d skew(const Eigen::Vector3d& v) noexcept {
        Eigen::Matrix3d s;
        s << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
        return s;
    }

    // Rotation by angle about the unit axis (Rodrigues).
    static Eigen::Matrix3d rotation(const Eigen::Vector3d& axis, double angle) noexcept {
        const double c = std::cos(angle), s = std::sin(angle);
        return c * Eigen::Matrix3d::Identity() + s * skew(axis) + (1.0 - c) * axis * axis.transpose();
    }

    // I x = L(x) [XX XY XZ YY YZ ZZ]^T.
    static Eigen::Matrix<double, 3, 6> inertia_map(const Eigen::Vector3d& x) noexcept {
        Eigen::Matrix<double, 3, 6> L;
        L << x.x(), x.y(), x.z(), 0.0, 0.0, 0.0,  //
            0.0, x.x(), 0.0, x.y(), x.z(), 0.0,   //
            0.0, 0.0, x.x(), 0.0, x.y(), x.z();
        return L;
    }

    void forward(const Joints& q, const Joints& qd, const Joints& qdd, std::array<LinkState, N>& links) const noexcept {
        const Eigen::Vector3d base_vd = -gravity_;
        for (int j = 0; j < chain_.size(); ++j) {
            const ChainJoint& joint = chain_.joint(j);
            const bool at_base = joint.antecedent < 0;
            const LinkState* parent = at_base ? nullptr : &links[static_cast<std::size_t>(joint.antecedent)];
            const Eigen::Vector3d w_a = at_base ? Eigen::Vector3d::Zero() : parent->w;
            const Eigen::Vector3d wd_a = at_base ? Eigen::Vector3d::Zero() : parent->wd;
            const Eigen::Vector3d vd_a = at_base ? base_vd : parent->vd;
            Eigen::Matrix3d R;
            Eigen::Vector3d p = joint.position;
            if (joint.type == JointType::Revolute) {
                R = joint.rotation * rotation(joint.axis, q[j]);
            } else {
                R = joint.rotation;
                p += joint.rotation * (joint.axis * q[j]);
            }
            LinkState& link = links[static_cast<std::size_t>(j)];
            const Eigen::Vector3d w_in_j = R.transpose() * w_a;
            link.vd = R.transpose() * (vd_a + wd_a.cross(p) + w_a.cross(w_a.cross(p)));
            link.wd = R.transpose() * wd_a;
            const Eigen::Vector3d joint_rate = joint.axis * qd[j];
            if (joint.type == JointType::Revolute) {
                link.w = w_in_j + joint_rate;
                link.wd += joint.axis * qdd[j] + w_in_j.cross(joint_rate);
            } else {
                link.w = w_in_j;
                link.vd += joint.axis * qdd[j] + 2.0 * w_in_j.cross(joint_rate);
            }
            link.R = R;
            link.p = p;
            link.R0 = at_base ? R : Eigen::Matrix3d(parent->R0 * R);
            link.o0 = at_base ? p : Eigen::Vector3d(parent->o0 + parent->R0 * p);
            link.z0 = link.R0 * joint.axis;
        }
    }

    // [f; n] at the link origin, in the link frame, = K [XX XY XZ YY YZ ZZ MX MY MZ M]^T.
    static Eigen::Matrix<double, 6, kInertialKinds> wrench_matrix(const LinkState& link) noexcept {
        Eigen::Matrix<double, 6, kInertialKinds> K;
        const Eigen::Matrix3d Sw = skew(link.w);
        K.template block<3, 6>(0, 0).setZero();
        K.template block<3, 3>(0, 6) = skew(link.wd) + Sw * Sw;
        K.template block<3, 1>(0, 9) = link.vd;
        K.template block<3, 6>(3, 0) = inertia_map(link.wd) + Sw * inertia_map(link.w);
        K.template block<3, 3>(3, 6) = -skew(link.vd);
        K.template block<3, 1>(3, 9).setZero();
        return K;
    }

private:
    KinematicChain<N> chain_;
    Eigen::Vector3d gravity_;
    StandardParameterOptions options_;
    std::array<CoulombSign, N> coulomb_{};
    Layout layout_;
};

}  // namespace jacobid::robot
