// SPDX-License-Identifier: MIT
#pragma once
// Forward dynamics of a serial (or tree) robot by Featherstone's articulated-body algorithm (ABA,
// Featherstone, "Rigid Body Dynamics Algorithms", 2008, ch. 7): qdd for the joint torques in O(n), without
// forming the inertia matrix. The model (chain, gravity, link inertias, rotor inertias) is built once; the
// per-call workspace is a caller-owned ArticulatedBodyData, so a call neither allocates nor copies the model
// (the model / data split of Pinocchio).
//
// Conventions are those of rnea_regressor.hpp, so that the same standard parameters give the same dynamics:
//  - spatial motion [w; v] and force [n; f] in a link's own frame, at the link origin;
//  - link j's inertia from its standard parameters about the link origin: the tensor I_O (XX .. ZZ), the
//    first moment h = (MX, MY, MZ) and the mass M, i.e. the spatial inertia [[I_O, S(h)], [-S(h), M 1]];
//  - gravity enters as the base acceleration a_0 = [0; -g];
//  - the rotor inertia IAj acts on joint j alone (tau_j += IAj qdd_j), so it adds to the joint's pivot
//    D_j = S_j^T I^A_j S_j + IAj and to nothing else;
//  - `tau` is the torque acting on the rigid bodies: the motor torque minus friction (FV, FC, FOFF), which
//    the caller subtracts, as for the inertia-matrix route.
// Articulated inertias are kept as 3x3 blocks [[A, B], [B^T, C]] and transformed block-wise (rotation, then
// shift of the reference point), which costs about half of the dense 6x6 product X^T I X.
//
// Every pivot D_j is positive exactly when the joint-space inertia matrix is positive definite (D_j is the
// Schur complement of the subtree's outer joints in M), so a non-positive pivot reports the parameters no
// rigid body can have, as a failed Cholesky factorization does on the inertia-matrix route.
#include <Eigen/Core>
#include <Eigen/Geometry>  // cross products
#include <array>
#include <cmath>

#include "jacobid/robot/kinematic_chain.hpp"
#include "jacobid/robot/regressor.hpp"
#include "jacobid/robot/standard_parameters.hpp"

namespace jacobid::robot {

enum class ArticulatedBodyStatus {
    Ok,
    NonFiniteInput,        // NaN or infinity in q, qd or tau
    NotPositiveDefinite,   // a pivot D_j <= 0: the inertia matrix at q is not positive definite
};

// One link's inertia about its own origin, in its own frame (the standard parameters XX .. M), and the
// rotor inertia of the joint that moves it.
struct LinkInertia {
    Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();  // I_O
    Eigen::Vector3d first_moment = Eigen::Vector3d::Zero();  // h = M c
    double mass = 0.0;
    double rotor_inertia = 0.0;  // IA
};

// Per-call workspace (one per thread of evaluation); its contents between calls mean nothing.
template <int N>
struct ArticulatedBodyData {
    std::array<Eigen::Matrix3d, N> R{};  // link frame in the antecedent frame, at q
    std::array<Eigen::Vector3d, N> p{};  // link origin in the antecedent frame, at q
    std::array<Eigen::Vector3d, N> w{}, v{};  // spatial velocity
    std::array<Eigen::Vector3d, N> cw{}, cv{};  // velocity-product acceleration v x S qd
    std::array<Eigen::Matrix3d, N> A{}, B{}, C{};  // articulated inertia blocks
    std::array<Eigen::Vector3d, N> pn{}, pf{};  // articulated bias force
    std::array<Eigen::Vector3d, N> Uw{}, Uv{};  // U = I^A S
    std::array<double, N> D_inv{}, u{};
    std::array<Eigen::Vector3d, N> aw{}, av{};  // spatial acceleration
};

template <int N>
class ArticulatedBody {
public:
    static constexpr int kMaxJoints = N;
    using Joints = JointVector<N>;
    using Data = ArticulatedBodyData<N>;

    // gravity: acceleration of gravity in the base frame, e.g. (0, 0, -9.81). Links start massless.
    ArticulatedBody(const KinematicChain<N>& chain, const Eigen::Vector3d& gravity) noexcept : chain_(chain), gravity_(gravity) {}

    void set_link(int j, const LinkInertia& link) noexcept {
        if (j >= 0 && j < N) links_[static_cast<std::size_t>(j)] = link;
    }
    const LinkInertia& link(int j) const noexcept { return links_[static_cast<std::size_t>(j)]; }

    // Every link from a standard parameter vector X laid out by `layout` (columns XXj .. Mj, IAj if present).
    template <typename Vector>
    void set_standard_parameters(const StandardParameterLayout<N>& layout, const Vector& X) noexcept {
        for (int j = 0; j < chain_.size(); ++j) {
            const auto at = [&](ParameterKind kind) { return static_cast<double>(X[layout.column(j, kind)]); };
            LinkInertia link;
            link.inertia << at(ParameterKind::XX), at(ParameterKind::XY), at(ParameterKind::XZ),  //
                at(ParameterKind::XY), at(ParameterKind::YY), at(ParameterKind::YZ),               //
                at(ParameterKind::XZ), at(ParameterKind::YZ), at(ParameterKind::ZZ);
            link.first_moment = Eigen::Vector3d(at(ParameterKind::MX), at(ParameterKind::MY), at(ParameterKind::MZ));
            link.mass = at(ParameterKind::M);
            link.rotor_inertia = layout.column(j, ParameterKind::IA) >= 0 ? at(ParameterKind::IA) : 0.0;
            set_link(j, link);
        }
    }

    int joint_count() const noexcept { return chain_.size(); }
    const KinematicChain<N>& chain() const noexcept { return chain_; }
    const Eigen::Vector3d& gravity() const noexcept { return gravity_; }

    // qdd for the rigid-body joint torques tau at (q, qd); qdd is untouched unless the status is Ok.
    ArticulatedBodyStatus forward_dynamics(const Joints& q, const Joints& qd, const Joints& tau, Data& data, Joints& qdd) const noexcept {
        const int n = chain_.size();
        for (int j = 0; j < n; ++j) {
            if (!std::isfinite(q[j]) || !std::isfinite(qd[j]) || !std::isfinite(tau[j])) return ArticulatedBodyStatus::NonFiniteInput;
        }
        velocities(q, qd, data);
        if (!articulated_inertias(tau, data)) return ArticulatedBodyStatus::NotPositiveDefinite;
        accelerations(data, qdd);
        return ArticulatedBodyStatus::Ok;
    }

private:
    static bool revolute(const ChainJoint& joint) noexcept { return joint.type == JointType::Revolute; }

    // Rotation by angle about the unit axis (Rodrigues), written out: no skew-matrix temporaries.
    static Eigen::Matrix3d rotation(const Eigen::Vector3d& a, double angle) noexcept {
        const double c = std::cos(angle), s = std::sin(angle), t = 1.0 - c;
        Eigen::Matrix3d r;
        r << c + t * a.x() * a.x(), t * a.x() * a.y() - s * a.z(), t * a.x() * a.z() + s * a.y(),  //
            t * a.x() * a.y() + s * a.z(), c + t * a.y() * a.y(), t * a.y() * a.z() - s * a.x(),    //
            t * a.x() * a.z() - s * a.y(), t * a.y() * a.z() + s * a.x(), c + t * a.z() * a.z();
        return r;
    }

    // R M R^T, written out: GCC leaves Eigen's 3x3 products out of line in a function this size, and the
    // calls cost as much as the arithmetic (callgrind on `jacobid simulate`). A symmetric M gives a
    // symmetric result: its upper triangle is computed and mirrored.
    template <bool Symmetric>
    static Eigen::Matrix3d congruence(const Eigen::Matrix3d& R, const Eigen::Matrix3d& M) noexcept {
        double t[3][3];  // M R^T
        for (int r = 0; r < 3; ++r) {
            for (int c = 0; c < 3; ++c) t[r][c] = M(r, 0) * R(c, 0) + M(r, 1) * R(c, 1) + M(r, 2) * R(c, 2);
        }
        Eigen::Matrix3d out;
        for (int r = 0; r < 3; ++r) {
            for (int c = Symmetric ? r : 0; c < 3; ++c) out(r, c) = R(r, 0) * t[0][c] + R(r, 1) * t[1][c] + R(r, 2) * t[2][c];
        }
        if (Symmetric) out(1, 0) = out(0, 1), out(2, 0) = out(0, 2), out(2, 1) = out(1, 2);
        return out;
    }

    // S(p) M, column by column: p x m_c.
    static Eigen::Matrix3d cross_columns(const Eigen::Vector3d& p, const Eigen::Matrix3d& M) noexcept {
        Eigen::Matrix3d out;
        for (int c = 0; c < 3; ++c) {
            out(0, c) = p.y() * M(2, c) - p.z() * M(1, c);
            out(1, c) = p.z() * M(0, c) - p.x() * M(2, c);
            out(2, c) = p.x() * M(1, c) - p.y() * M(0, c);
        }
        return out;
    }

    static Eigen::Matrix3d skew(const Eigen::Vector3d& v) noexcept {
        Eigen::Matrix3d s;
        s << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
        return s;
    }

    // Pass 1 (base to tips): link transforms, velocities, velocity-product accelerations, rigid-body
    // inertias and bias forces as the starting articulated quantities.
    void velocities(const Joints& q, const Joints& qd, Data& d) const noexcept {
        for (int j = 0; j < chain_.size(); ++j) {
            const auto js = static_cast<std::size_t>(j);
            const ChainJoint& joint = chain_.joint(j);
            const LinkInertia& link = links_[js];
            Eigen::Matrix3d& R = d.R[js];
            Eigen::Vector3d& p = d.p[js];
            p = joint.position;
            if (revolute(joint) && joint.axis == Eigen::Vector3d::UnitZ()) {
                // The MDH case (every MDH joint turns about z): R = R_fixed Rot(z, q), two columns mixed.
                const double c = std::cos(q[j]), s = std::sin(q[j]);
                R.col(0) = c * joint.rotation.col(0) + s * joint.rotation.col(1);
                R.col(1) = c * joint.rotation.col(1) - s * joint.rotation.col(0);
                R.col(2) = joint.rotation.col(2);
            } else if (revolute(joint)) {
                R.noalias() = joint.rotation * rotation(joint.axis, q[j]);
            } else {
                R = joint.rotation;
                p.noalias() += joint.rotation * (joint.axis * q[j]);
            }
            Eigen::Vector3d& w = d.w[js];
            Eigen::Vector3d& v = d.v[js];
            if (joint.antecedent < 0) {
                w.setZero();
                v.setZero();
            } else {
                const auto a = static_cast<std::size_t>(joint.antecedent);
                w.noalias() = R.transpose() * d.w[a];
                v.noalias() = R.transpose() * (d.v[a] - p.cross(d.w[a]));
            }
            const Eigen::Vector3d rate = joint.axis * qd[j];
            // c = v x (S qd) with v the link's velocity before its own joint's contribution (S x S = 0).
            if (revolute(joint)) {
                d.cw[js] = w.cross(rate);
                d.cv[js] = v.cross(rate);
                w += rate;
            } else {
                d.cw[js].setZero();
                d.cv[js] = w.cross(rate);
                v += rate;
            }
            // Rigid-body inertia and bias force v x* (I v).
            const Eigen::Matrix3d Sh = skew(link.first_moment);
            d.A[js] = link.inertia;
            d.B[js] = Sh;
            d.C[js] = link.mass * Eigen::Matrix3d::Identity();
            const Eigen::Vector3d hn = link.inertia * w + link.first_moment.cross(v);  // angular momentum
            const Eigen::Vector3d hf = link.mass * v - link.first_moment.cross(w);     // linear momentum
            d.pn[js] = w.cross(hn) + v.cross(hf);
            d.pf[js] = w.cross(hf);
        }
    }

    // Pass 2 (tips to base): pivots, and each articulated body handed to its antecedent.
    bool articulated_inertias(const Joints& tau, Data& d) const noexcept {
        for (int j = chain_.size() - 1; j >= 0; --j) {
            const auto js = static_cast<std::size_t>(j);
            const ChainJoint& joint = chain_.joint(j);
            const Eigen::Vector3d& s = joint.axis;
            Eigen::Matrix3d &A = d.A[js], &B = d.B[js], &C = d.C[js];
            Eigen::Vector3d &Uw = d.Uw[js], &Uv = d.Uv[js];
            double D = links_[js].rotor_inertia;
            if (revolute(joint)) {
                Uw.noalias() = A * s;
                Uv.noalias() = B.transpose() * s;
                D += s.dot(Uw);
                d.u[js] = tau[j] - s.dot(d.pn[js]);
            } else {
                Uw.noalias() = B * s;
                Uv.noalias() = C * s;
                D += s.dot(Uv);
                d.u[js] = tau[j] - s.dot(d.pf[js]);
            }
            if (!(D > 0.0) || !std::isfinite(D)) return false;
            d.D_inv[js] = 1.0 / D;
            if (joint.antecedent < 0) continue;
            // I^a = I^A - U U^T / D and p^a = p^A + I^a c + U u / D, in link j's frame ...
            const Eigen::Vector3d Uw_d = Uw * d.D_inv[js], Uv_d = Uv * d.D_inv[js];
            A.noalias() -= Uw_d * Uw.transpose();
            B.noalias() -= Uw_d * Uv.transpose();
            C.noalias() -= Uv_d * Uv.transpose();
            const Eigen::Vector3d &cw = d.cw[js], &cv = d.cv[js];
            const Eigen::Vector3d pn = d.pn[js] + A * cw + B * cv + Uw_d * d.u[js];
            const Eigen::Vector3d pf = d.pf[js] + B.transpose() * cw + C * cv + Uv_d * d.u[js];
            // ... then in the antecedent's frame and about its origin: rotate by R, shift by p.
            const auto a = static_cast<std::size_t>(joint.antecedent);
            const Eigen::Matrix3d& R = d.R[js];
            const Eigen::Matrix3d Ar = congruence<true>(R, A);
            const Eigen::Matrix3d Br = congruence<false>(R, B);
            const Eigen::Matrix3d Cr = congruence<true>(R, C);
            const Eigen::Vector3d& p = d.p[js];
            const Eigen::Matrix3d PC = cross_columns(p, Cr);
            const Eigen::Matrix3d PBt = cross_columns(p, Br.transpose());
            // A_O = A' + P B'^T - B' P - P C' P with P = S(p) (P^T = -P, so that X P = -(P X^T)^T),
            // B_O = B' + P C', C_O = C'.
            d.A[a] += Ar + PBt + PBt.transpose() + cross_columns(p, PC.transpose()).transpose();
            d.B[a] += Br + PC;
            d.C[a] += Cr;
            const Eigen::Vector3d f = R * pf;
            d.pf[a] += f;
            d.pn[a] += R * pn + d.p[js].cross(f);
        }
        return true;
    }

    // Pass 3 (base to tips): joint accelerations.
    void accelerations(Data& d, Joints& qdd) const noexcept {
        const Eigen::Vector3d base_v = -gravity_;
        for (int j = 0; j < chain_.size(); ++j) {
            const auto js = static_cast<std::size_t>(j);
            const ChainJoint& joint = chain_.joint(j);
            const Eigen::Matrix3d& R = d.R[js];
            Eigen::Vector3d &aw = d.aw[js], &av = d.av[js];
            if (joint.antecedent < 0) {
                aw = d.cw[js];
                av.noalias() = R.transpose() * base_v;
                av += d.cv[js];
            } else {
                const auto a = static_cast<std::size_t>(joint.antecedent);
                aw.noalias() = R.transpose() * d.aw[a];
                av.noalias() = R.transpose() * (d.av[a] - d.p[js].cross(d.aw[a]));
                aw += d.cw[js];
                av += d.cv[js];
            }
            const double qdd_j = (d.u[js] - d.Uw[js].dot(aw) - d.Uv[js].dot(av)) * d.D_inv[js];
            qdd[j] = qdd_j;
            if (revolute(joint)) {
                aw += joint.axis * qdd_j;
            } else {
                av += joint.axis * qdd_j;
            }
        }
    }

    KinematicChain<N> chain_;
    Eigen::Vector3d gravity_;
    std::array<LinkInertia, N> links_{};
};

}  // namespace jacobid::robot
