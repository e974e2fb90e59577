// SPDX-License-Identifier: MIT
#include <Eigen/Core>  // before AutoDiff, which does not include it
#include <Eigen/Geometry>
#include <unsupported/Eigen/AutoDiff>
#include <array>
#include <cmath>
#include <vector>

#include "excite/serial_derivative_routes.hpp"

namespace jacobid::excite {
namespace {

using robot::ChainJoint;
using robot::JointType;
using robot::ParameterKind;
constexpr int kMaxJoints = robot::kMaxSerialJoints;

// Forward-mode AD of the rigid-body regressor of a serial robot. One class for every joint count: the 3n derivative
// lanes are a vector of run-time size within a fixed capacity (no heap per operation), so the route is compiled once,
// not once per joint count like the adjoint (it is the independent check, not the route designs run on).
class Automatic final : public RegressorDerivatives {
public:
    using Lanes = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 3 * kMaxJoints, 1>;
    using AD = Eigen::AutoDiffScalar<Lanes>;
    using V3 = Eigen::Matrix<AD, 3, 1>;
    using M3 = Eigen::Matrix<AD, 3, 3>;

    explicit Automatic(const robot::SerialRobotModel& model) : n_(model.joint_count()), layout_(model.joint_count(), model.config().options) {
        const auto& config = model.config();
        for (int j = 0; j < n_; ++j) {
            const auto J = static_cast<std::size_t>(j);
            joints_[J] = config.joints[J];
            joints_[J].axis.normalize();
            coulomb_[J] = J < config.joint_coulomb.size() ? config.joint_coulomb[J] : config.options.coulomb;
        }
        gravity_ = config.gravity;
        const auto& base = model.base().base_columns;
        standard_of_base_.assign(base.begin(), base.end());
        standard_count_ = layout_.count();
    }
    DerivativeRoute route() const override { return DerivativeRoute::Automatic; }

    void evaluate(const double* q, const double* qd, const double* qdd, const Eigen::Ref<const Eigen::MatrixXd>& H, const Eigen::VectorXd& x, Eigen::VectorXd& dphi,
                  Eigen::MatrixXd* dtau) const override {
        const int n = n_;
        // The base-parameter weights on their standard columns (every other standard column weighs 0).
        Eigen::MatrixXd Hs = Eigen::MatrixXd::Zero(n, standard_count_);
        Eigen::VectorXd xs = Eigen::VectorXd::Zero(standard_count_);
        const bool with_phi = H.size() > 0;
        for (std::size_t b = 0; b < standard_of_base_.size(); ++b) {
            if (with_phi) Hs.col(standard_of_base_[b]) = H.col(static_cast<Eigen::Index>(b));
            xs[standard_of_base_[b]] = x[static_cast<Eigen::Index>(b)];
        }
        std::array<LinkState, kMaxJoints> links;
        forward(q, qd, qdd, links);
        AD phi = constant(0.0);
        std::array<AD, kMaxJoints> tau;
        tau.fill(constant(0.0));
        for (int j = 0; j < n; ++j) {
            const LinkState& link = links[static_cast<std::size_t>(j)];
            const Eigen::Matrix<AD, 6, robot::kInertialKinds> K = wrench_matrix(link);
            const int first = layout_.column(j, ParameterKind::XX);
            // The wrench of link j for the torque's parameters and, per carrying joint i, for H's row i.
            const Eigen::Matrix<AD, 6, 1> f_tau = K * xs.segment<robot::kInertialKinds>(first).cast<AD>();
            for (int i = j; i >= 0; i = joints_[static_cast<std::size_t>(i)].antecedent) {
                const LinkState& carrier = links[static_cast<std::size_t>(i)];
                Eigen::Matrix<AD, 1, 6> e;
                const V3 z_in_j = link.R0.transpose() * carrier.z0;
                if (joints_[static_cast<std::size_t>(i)].type == JointType::Revolute) {
                    e.head<3>() = (link.R0.transpose() * carrier.z0.cross(link.o0 - carrier.o0)).transpose();
                    e.tail<3>() = z_in_j.transpose();
                } else {
                    e.head<3>() = z_in_j.transpose();
                    e.tail<3>().setConstant(constant(0.0));
                }
                tau[static_cast<std::size_t>(i)] += e.dot(f_tau);
                if (with_phi) {
                    const Eigen::Matrix<AD, 6, 1> f_phi = K * Hs.row(i).segment(first, robot::kInertialKinds).transpose().cast<AD>();
                    phi += e.dot(f_phi);
                }
            }
        }
        dphi.setZero(3 * n);
        if (with_phi) dphi = phi.derivatives();
        Eigen::MatrixXd dt(n, 3 * n);
        for (int i = 0; i < n; ++i) dt.row(i) = tau[static_cast<std::size_t>(i)].derivatives().transpose();
        // Rotor inertia, viscous and Coulomb friction act on their own joint: d/dqdd_j IA, d/dqd_j FV, s'(qd_j) FC.
        for (int j = 0; j < n; ++j) {
            const double slope = coulomb_[static_cast<std::size_t>(j)].slope(qd[j]);
            const int ia = layout_.column(j, ParameterKind::IA), fv = layout_.column(j, ParameterKind::FV), fc = layout_.column(j, ParameterKind::FC);
            if (ia >= 0) {
                dt(j, 2 * n + j) += xs[ia];
                if (with_phi) dphi[2 * n + j] += Hs(j, ia);
            }
            dt(j, n + j) += xs[fv] + slope * xs[fc];
            if (with_phi) dphi[n + j] += Hs(j, fv) + slope * Hs(j, fc);
        }
        if (dtau) *dtau = dt;
    }

private:
    struct LinkState {
        V3 w, wd, vd, o0, z0;
        M3 R0;
    };

    // Constants carry all 3n lanes as zeros, so every kinematic quantity has lanes of one size. The parameters and
    // weights cast to AD (`cast<AD>()`: lanes of size 0) only ever multiply a full-size operand, where Eigen's AutoDiff
    // makes the two coherent (make_coherent resizes the empty one to zeros).
    AD constant(double v) const { return AD(v, Lanes::Zero(3 * n_)); }
    AD lane(double v, int k) const { return AD(v, 3 * n_, k); }
    V3 constant_vector(const Eigen::Vector3d& v) const { return V3(constant(v.x()), constant(v.y()), constant(v.z())); }
    M3 constant_matrix(const Eigen::Matrix3d& m) const {
        M3 out;
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c) out(r, c) = constant(m(r, c));
        return out;
    }

    M3 skew(const V3& v) const {
        M3 s;
        s << constant(0.0), -v.z(), v.y(), v.z(), constant(0.0), -v.x(), -v.y(), v.x(), constant(0.0);
        return s;
    }

    Eigen::Matrix<AD, 3, 6> inertia_map(const V3& x) const {
        const AD z = constant(0.0);
        Eigen::Matrix<AD, 3, 6> L;
        L << x.x(), x.y(), x.z(), z, z, z,  //
            z, x.x(), z, x.y(), x.z(), z,   //
            z, z, x.x(), z, x.y(), x.z();
        return L;
    }

    Eigen::Matrix<AD, 6, robot::kInertialKinds> wrench_matrix(const LinkState& link) const {
        Eigen::Matrix<AD, 6, robot::kInertialKinds> K;
        K.setConstant(constant(0.0));
        const M3 Sw = skew(link.w);
        K.block<3, 3>(0, 6) = skew(link.wd) + Sw * Sw;
        K.block<3, 1>(0, 9) = link.vd;
        K.block<3, 6>(3, 0) = inertia_map(link.wd) + Sw * inertia_map(link.w);
        K.block<3, 3>(3, 6) = -skew(link.vd);
        return K;
    }

    void forward(const double* q, const double* qd, const double* qdd, std::array<LinkState, kMaxJoints>& links) const {
        const V3 zero = constant_vector(Eigen::Vector3d::Zero());
        const V3 base_vd = constant_vector(-gravity_);
        for (int j = 0; j < n_; ++j) {
            const ChainJoint& joint = joints_[static_cast<std::size_t>(j)];
            const bool at_base = joint.antecedent < 0;
            const LinkState* parent = at_base ? nullptr : &links[static_cast<std::size_t>(joint.antecedent)];
            const V3 w_a = at_base ? zero : parent->w, wd_a = at_base ? zero : parent->wd, vd_a = at_base ? base_vd : parent->vd;
            const AD qj = lane(q[j], j), qdj = lane(qd[j], n_ + j), qddj = lane(qdd[j], 2 * n_ + j);
            const V3 axis = constant_vector(joint.axis);
            M3 R = constant_matrix(joint.rotation);
            V3 p = constant_vector(joint.position);
            if (joint.type == JointType::Revolute) {
                // Rodrigues: c I + s [a]x + (1 - c) a a^T.
                const AD c = cos(qj), s = sin(qj);
                const M3 turn = constant_matrix(Eigen::Matrix3d::Identity()) * c + skew(axis) * s + (axis * axis.transpose()) * (constant(1.0) - c);
                R = R * turn;
            } else {
                p += R * (axis * qj);  // R is still the joint's fixed rotation
            }
            LinkState& link = links[static_cast<std::size_t>(j)];
            const M3 Rt = R.transpose();
            const V3 w_in_j = Rt * w_a;
            link.vd = Rt * (vd_a + wd_a.cross(p) + w_a.cross(w_a.cross(p)));
            link.wd = Rt * wd_a;
            const V3 joint_rate = axis * qdj;
            if (joint.type == JointType::Revolute) {
                link.w = w_in_j + joint_rate;
                link.wd += axis * qddj + w_in_j.cross(joint_rate);
            } else {
                link.w = w_in_j;
                link.vd += axis * qddj + w_in_j.cross(joint_rate) * constant(2.0);
            }
            link.R0 = at_base ? R : M3(parent->R0 * R);
            link.o0 = at_base ? p : V3(parent->o0 + parent->R0 * p);
            link.z0 = link.R0 * axis;
        }
    }

    int n_;
    robot::StandardParameterLayout<kMaxJoints> layout_;
    std::array<ChainJoint, kMaxJoints> joints_{};
    std::array<robot::CoulombSign, kMaxJoints> coulomb_{};
    Eigen::Vector3d gravity_;
    std::vector<int> standard_of_base_;
    int standard_count_ = 0;
};

}  // namespace

std::unique_ptr<RegressorDerivatives> make_automatic_derivatives(const robot::SerialRobotModel& model) {
    if (model.joint_count() < 1 || model.joint_count() > kMaxJoints) return nullptr;
    return std::make_unique<Automatic>(model);
}

}  // namespace jacobid::excite
