// SPDX-License-Identifier: MIT
#pragma once
// Reverse-mode (adjoint) derivatives of one contraction of the RNEA regressor (rnea_regressor.hpp):
//   phi(q, qd, qdd) = <H, D(q, qd, qdd)> = sum_ik H_ik D_ik(q, qd, qdd),
// H a fixed weight matrix (joints x standard parameters). All 3n partial derivatives of phi come from the
// regressor's own forward Newton-Euler pass and one adjoint pass through it: a few regressor costs, whatever
// the number of joints, where central differences need 5n + 1 regressor calls and forward-mode automatic
// differentiation carries 3n derivative lanes through every operation. What `jacobid excite` needs: its
// criterion's gradient is, per sample, the regressor's derivative contracted with dF/dW at that sample's rows
// (docs/excite.md, "Speed"); a torque tau_i = D_i. X is the contraction with H = e_i X^T.
//
// The forward pass, as in RneaRegressor (link frames; a the antecedent, R and p joint j's rotation and origin in
// a's frame, t = vd_a + wd_a x p + w_a x (w_a x p)):
//   w_j = R^T w_a + z qd_j (revolute) | R^T w_a (prismatic)
//   wd_j = R^T wd_a + z qdd_j + (R^T w_a) x z qd_j (revolute) | R^T wd_a (prismatic)
//   vd_j = R^T t (revolute) | R^T t + z qdd_j + 2 (R^T w_a) x z qd_j (prismatic)
//   R0_j = R0_a R, o0_j = o0_a + R0_a p, z0_j = R0_j z; R = J rot(z, q_j) (revolute), p = P + J z q_j (prismatic)
// and per link j and carrying joint i (i = j and its ancestors), with h the 10 weights of H's row i on link
// j's inertial columns (inertia I, first moments s, mass m) and K_j the wrench matrix,
//   phi_ij = e_ij . K_j h = ef . (wd x s + w x (w x s) + m vd) + en . (I wd + w x (I w) + s x vd),
//   e_ij = (ef, en) = (R0_j^T (z0_i x (o0_j - o0_i)), R0_j^T z0_i) (revolute i) | (R0_j^T z0_i, 0) (prismatic i).
// The adjoint pass runs it backwards: first every pair's adjoints of (w, wd, vd)_j (the gradients of phi_ij
// written out below), of R0_j, o0_j, o0_i and z0_i (the adjoint of e_ij is K_j h); then the links from the
// leaves to the base, each passing its adjoints to its antecedent and giving its joint's three partial
// derivatives. The rotations' adjoints are carried in the base frame as 3-vectors, not 3 x 3 matrices: R0_l of
// every link l below a revolute joint k turns with q_k about z0_k and o0_l about (z0_k, o0_k), so d phi / dq_k
// gets z0_k . (sum over l below k of rho_l + (o0_l - o0_k) x ob_l), rho_l = vee(Rb_l R0_l^T - R0_l Rb_l^T) the
// adjoint of R0_l as a vector (an outer product x y^T in it contributes (R0_l y) x x) and ob_l that of o0_l; a
// prismatic joint k moves them all by z0_k; the local rotation R of the link frames' recursion gives
// z . (y x (R^T x)) per outer product x y^T of its adjoint. Friction and rotor inertia act on their own joint:
// d/dqdd IA, d/dqd FV, s'(qd) FC. Everything is fixed-size: no allocation. Several contractions share one pass
// as lanes (torque_gradient: the n torques).
#include <Eigen/Core>
#include <array>
#include <cmath>

#include "jacobid/robot/rnea_regressor.hpp"

namespace jacobid::robot {

template <int N>
class RneaRegressorAdjoint {
public:
    using Regression = RneaRegressor<N>;
    using Weights = typename Regression::Regressor;  // H: the regressor's shape
    using Joints = typename Regression::Joints;
    using Links = std::array<typename Regression::LinkState, N>;

    // The regressor must outlive the adjoint.
    explicit RneaRegressorAdjoint(const Regression& regressor) noexcept : r_(regressor) {}

    // The forward pass at one state, shared by every gradient() at that state.
    RegressorStatus kinematics(const Joints& q, const Joints& qd, const Joints& qdd, Links& links) const noexcept {
        for (int j = 0; j < r_.joint_count(); ++j) {
            if (!std::isfinite(q[j]) || !std::isfinite(qd[j]) || !std::isfinite(qdd[j])) return RegressorStatus::NonFiniteInput;
        }
        r_.forward(q, qd, qdd, links);
        return RegressorStatus::Ok;
    }

    // d phi / dq, d phi / dqd, d phi / dqdd of phi = <H, D(q, qd, qdd)> (the first joint_count() rows and
    // parameter_count() columns of H), at the state `links` holds (kinematics() at q, qd, qdd; qd: the same).
    // A link's block of a row of H that is exactly zero costs nothing.
    void gradient(const Joints& qd, const Links& links, const Weights& H, Joints& gq, Joints& gqd, Joints& gqdd) const noexcept {
        const auto& layout = r_.layout();
        Eigen::Matrix<double, 1, N> dq, dqd, dqdd;
        pass<1, false>(
            qd, links, [&](int i, int j) { return H.row(i).template segment<kInertialKinds>(layout.column(j, ParameterKind::XX)).transpose(); },
            [&](int j) { return own_weights(j, [&](int column) { return H(j, column); }); }, [](int) { return 0; }, dq, dqd, dqdd);
        gq = dq.transpose(), gqd = dqd.transpose(), gqdd = dqdd.transpose();
    }

    using Square = Eigen::Matrix<double, N, N>;
    using Parameters = typename Regression::Parameters;

    // The torque's derivatives, tau = D(q, qd, qdd) X (the first parameter_count() entries of X): (i, j) of dq, dqd, dqdd
    // is d tau_i / dq_j, d tau_i / dqd_j, d tau_i / dqdd_j. The n contractions tau_i = <e_i X^T, D> in one pass with
    // n lanes (lane i: tau_i), where gradient() would take n passes.
    void torque_gradient(const Joints& qd, const Links& links, const Parameters& X, Square& dq, Square& dqd, Square& dqdd) const noexcept {
        const auto& layout = r_.layout();
        pass<N, true>(
            qd, links, [&](int, int j) { return X.template segment<kInertialKinds>(layout.column(j, ParameterKind::XX)); },
            [&](int j) { return own_weights(j, [&](int column) { return X[column]; }); }, [](int i) { return i; }, dq, dqd, dqdd);
    }

private:
    // The weights of joint j's own columns (IA, FV, FC; IA 0 when switched off), weight(column) read from H or X.
    template <typename Weight>
    Eigen::Vector3d own_weights(int j, Weight weight) const noexcept {
        const auto& layout = r_.layout();
        const int ia = layout.column(j, ParameterKind::IA);
        return {ia >= 0 ? weight(ia) : 0.0, weight(layout.column(j, ParameterKind::FV)), weight(layout.column(j, ParameterKind::FC))};
    }

    // Whether every weight is exactly 0 (that pair then costs nothing): a plain loop, which the compiler inlines,
    // where (h.array() == 0.0).all() stayed a call of ~150 instructions per pair (3 % of an evaluation, callgrind).
    static bool all_zero(const Eigen::Matrix<double, kInertialKinds, 1>& h) noexcept {
        bool zero = true;
        for (int k = 0; k < kInertialKinds; ++k) zero = zero && h[k] == 0.0;
        return zero;
    }

    // K_j h without forming K_j (Regression::wrench_matrix): the force and moment of link j's motion for the
    // inertial parameters h = (XX, XY, XZ, YY, YZ, ZZ, MX, MY, MZ, M): (wd x s + w x (w x s) + m vd, I wd + w x (I w) + s x vd).
    static Eigen::Matrix<double, 6, 1> link_wrench(const typename Regression::LinkState& link, const Eigen::Matrix<double, kInertialKinds, 1>& h) noexcept {
        Eigen::Matrix3d I;
        I << h[0], h[1], h[2], h[1], h[3], h[4], h[2], h[4], h[5];
        const Eigen::Vector3d s = h.template segment<3>(6), Iw = I * link.w;
        Eigen::Matrix<double, 6, 1> f;
        f.template head<3>() = link.wd.cross(s) + link.w.cross(link.w.cross(s)) + h[9] * link.vd;
        f.template tail<3>() = I * link.wd + link.w.cross(Iw) + s.cross(link.vd);
        return f;
    }

    // One adjoint pass for L contractions: weights(i, j) the 10 inertial weights of carrier i's row on link j's columns,
    // lane(i) the contraction they belong to, own(j) joint j's own (IA, FV, FC) weights (in lane(j)). Out: (l, j) =
    // d phi_l / d(q_j, qd_j, qdd_j). kSameForEveryCarrier: weights(i, j) does not depend on i (the torques: X), so
    // what follows from them alone (K_j h and its base-frame halves) is computed once per link, not once per pair.
    template <int L, bool kSameForEveryCarrier, typename PairWeights, typename OwnWeights, typename Lane>
    void pass(const Joints& qd, const Links& links, PairWeights weights, OwnWeights own, Lane lane, Eigen::Matrix<double, L, N>& dq,
              Eigen::Matrix<double, L, N>& dqd, Eigen::Matrix<double, L, N>& dqdd) const noexcept {
        using V3 = Eigen::Vector3d;
        using M3 = Eigen::Matrix3d;
        using Lanes = Eigen::Matrix<double, 3, L>;
        const int n = r_.joint_count();
        // Per link, 3 x L: adjoints of w, wd, vd (link frame); rho, ob and o0 x ob summed over the link and
        // everything below it (base frame).
        std::array<Lanes, N> bw, bwd, bvd, rho, ob, moment;
        for (int j = 0; j < n; ++j) {
            const auto k = static_cast<std::size_t>(j);
            bw[k].setZero(), bwd[k].setZero(), bvd[k].setZero(), rho[k].setZero(), ob[k].setZero(), moment[k].setZero();
        }
        dq.setZero(), dqd.setZero(), dqdd.setZero();
        for (int j = 0; j < n; ++j) {
            const auto k = static_cast<std::size_t>(j);
            const auto& link = links[k];
            // K_j h for each carrier's h; with the same h for every carrier, that one wrench directly (link_wrench).
            Eigen::Matrix<double, 6, kInertialKinds> K;
            if constexpr (!kSameForEveryCarrier) K = Regression::wrench_matrix(link);
            const V3& w = link.w;
            Eigen::Matrix<double, kInertialKinds, 1> h;
            V3 a, b;  // R0_j times the halves of f = K_j h, the adjoint of e_ij
            bool ready = false;
            for (int i = j; i >= 0; i = r_.chain().joint(i).antecedent) {
                if (!kSameForEveryCarrier || !ready) {
                    h = weights(i, j);
                    if (all_zero(h)) {
                        if (kSameForEveryCarrier) break;
                        continue;
                    }
                    Eigen::Matrix<double, 6, 1> f;
                    if constexpr (kSameForEveryCarrier) {
                        f = link_wrench(link, h);
                    } else {
                        f.noalias() = K * h;
                    }
                    a.noalias() = link.R0 * f.template head<3>();
                    b.noalias() = link.R0 * f.template tail<3>();
                    ready = true;
                }
                const auto c = static_cast<std::size_t>(i);
                const int l = lane(i);
                const auto& carrier = links[c];
                V3 ef, en;
                if (r_.chain().joint(i).type == JointType::Revolute) {
                    const V3 d = link.o0 - carrier.o0, u = carrier.z0.cross(d), moved = a.cross(carrier.z0);
                    ef.noalias() = link.R0.transpose() * u;
                    en.noalias() = link.R0.transpose() * carrier.z0;
                    rho[k].col(l) += a.cross(u) + b.cross(carrier.z0);
                    rho[c].col(l) += carrier.z0.cross(d.cross(a) + b);
                    ob[k].col(l) += moved;
                    moment[k].col(l) += link.o0.cross(moved);
                    ob[c].col(l) -= moved;
                    moment[c].col(l) -= carrier.o0.cross(moved);
                } else {
                    ef.noalias() = link.R0.transpose() * carrier.z0;
                    en.setZero();
                    rho[k].col(l) += a.cross(carrier.z0);
                    rho[c].col(l) += carrier.z0.cross(a);
                }
                // K_j's own dependence on link j's w, wd, vd.
                M3 I;
                I << h[0], h[1], h[2], h[1], h[3], h[4], h[2], h[4], h[5];
                const V3 s = h.template segment<3>(6);
                bvd[k].col(l) += h[9] * ef + en.cross(s);
                bwd[k].col(l) += s.cross(ef) + I * en;
                bw[k].col(l) += ef * w.dot(s) + s * ef.dot(w) - (2.0 * ef.dot(s)) * w + (I * w).cross(en) + I * en.cross(w);
            }
            const V3 mine = own(j);
            dqdd(lane(j), j) += mine[0];
            dqd(lane(j), j) += mine[1] + r_.coulomb(j).slope(qd[j]) * mine[2];
        }
        for (int j = n - 1; j >= 0; --j) {
            const auto k = static_cast<std::size_t>(j);
            const ChainJoint& joint = r_.chain().joint(j);
            const auto& link = links[k];
            const bool at_base = joint.antecedent < 0, revolute = joint.type == JointType::Revolute;
            const auto* parent = at_base ? nullptr : &links[static_cast<std::size_t>(joint.antecedent)];
            // t = vd_a + wd_a x p + w_a x (w_a x p) is linear in vd_a: its adjoint needs the values of w_a and wd_a only.
            const V3 w_a = at_base ? V3::Zero() : parent->w, wd_a = at_base ? V3::Zero() : parent->wd;
            const M3& R = link.R;
            const V3& p = link.p;
            const V3 w_in = R.transpose() * w_a, rate = joint.axis * qd[j];
            Lanes bw_in = bw[k], brate;
            if (revolute) {
                dqd.col(j) += (joint.axis.transpose() * bw[k]).transpose();
                dqdd.col(j) += (joint.axis.transpose() * bwd[k]).transpose();
                bw_in.noalias() += Regression::skew(rate) * bwd[k];
                brate.noalias() = -Regression::skew(w_in) * bwd[k];
            } else {
                dqdd.col(j) += (joint.axis.transpose() * bvd[k]).transpose();
                bw_in.noalias() += 2.0 * Regression::skew(rate) * bvd[k];
                brate.noalias() = -2.0 * Regression::skew(w_in) * bvd[k];
            }
            dqd.col(j) += (joint.axis.transpose() * brate).transpose();
            const Lanes bt = R * bvd[k];  // vd = R^T t + .., t = vd_a + wd_a x p + w_a x (w_a x p)
            Lanes bw_a = R * bw_in + w_a.dot(p) * bt;
            bw_a.noalias() += p * (w_a.transpose() * bt);
            bw_a.noalias() -= 2.0 * w_a * (p.transpose() * bt);
            Lanes bwd_a = R * bwd[k];
            bwd_a.noalias() += Regression::skew(p) * bt;
            if (revolute) {
                // The local rotation (w = R^T w_a + .., wd = R^T wd_a + .., vd = R^T t), in the link frame; the
                // base-frame turn of everything below, rho + (o0_l - o0_j) x ob.
                const V3 wd_in = R.transpose() * wd_a;
                Lanes local = -Regression::skew(w_in) * bw_in;
                local.noalias() -= Regression::skew(wd_in) * bwd[k];
                local.noalias() -= Regression::skew(link.vd) * bvd[k];
                Lanes world = rho[k] + moment[k];
                world.noalias() -= Regression::skew(link.o0) * ob[k];
                dq.col(j) += (joint.axis.transpose() * local + link.z0.transpose() * world).transpose();
            } else {
                // p = P + J z q_j in t, and every origin below moved along z0_j.
                Lanes bp = -Regression::skew(wd_a) * bt;
                bp.noalias() += w_a * (w_a.transpose() * bt);
                bp -= w_a.squaredNorm() * bt;
                dq.col(j) += ((R * joint.axis).transpose() * bp + link.z0.transpose() * ob[k]).transpose();
            }
            if (!at_base) {
                const auto a = static_cast<std::size_t>(joint.antecedent);
                rho[a] += rho[k];
                ob[a] += ob[k];
                moment[a] += moment[k];
                bw[a] += bw_a;
                bwd[a] += bwd_a;
                bvd[a] += bt;
            }
        }
    }

    const Regression& r_;
};

}  // namespace jacobid::robot
