// SPDX-License-Identifier: MIT
#include "excite/regressor_derivatives.hpp"

#include <unsupported/Eigen/AutoDiff>

#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "jacobid/robot/rnea_regressor_adjoint.hpp"
#include "robot/serial_robot_model.hpp"

namespace jacobid::excite {
namespace {

using robot::ChainJoint;
using robot::JointType;
using robot::ParameterKind;

// Central differences of any model's regressor.
class CentralDifferences final : public RegressorDerivatives {
public:
    explicit CentralDifferences(const robot::RobotModel& model) : model_(model) {}
    DerivativeRoute route() const override { return DerivativeRoute::CentralDifferences; }

    void evaluate(const double* q0, const double* qd0, const double* qdd0, const Eigen::Ref<const Eigen::MatrixXd>& H, const Eigen::VectorXd& x, Eigen::VectorXd& dphi,
                  Eigen::MatrixXd* dtau) const override {
        constexpr double kStep = 1e-6;
        const int n = model_.joint_count(), p = model_.parameter_count();
        Eigen::VectorXd q = Eigen::Map<const Eigen::VectorXd>(q0, n), qd = Eigen::Map<const Eigen::VectorXd>(qd0, n),
                        qdd = Eigen::Map<const Eigen::VectorXd>(qdd0, n);
        Eigen::MatrixXd Y(n, p), plus(n, p), minus(n, p), d(n, p);
        model_.regressor(q.data(), qd.data(), qdd.data(), Y);
        dphi.setZero(3 * n);
        if (dtau) dtau->resize(n, 3 * n);
        auto store = [&](int lane) {
            if (H.size() > 0) dphi[lane] = H.cwiseProduct(d).sum();
            if (dtau) dtau->col(lane) = d * x;
        };
        auto central = [&](Eigen::VectorXd& v, int j, int lane) {
            const double h = kStep * std::max(1.0, std::abs(v[j]));
            v[j] += h;
            model_.regressor(q.data(), qd.data(), qdd.data(), plus);
            v[j] -= 2.0 * h;
            model_.regressor(q.data(), qd.data(), qdd.data(), minus);
            v[j] += h;
            d = (plus - minus) / (2.0 * h);
            store(lane);
        };
        for (int j = 0; j < n; ++j) {
            central(q, j, j);
            central(qd, j, n + j);
            qdd[j] += 1.0;  // Y is linear in qdd: the difference is the exact derivative
            model_.regressor(q.data(), qd.data(), qdd.data(), plus);
            qdd[j] -= 1.0;
            d = plus - Y;
            store(2 * n + j);
        }
    }

private:
    const robot::RobotModel& model_;
};

// Forward-mode AD of the rigid-body regressor of an N-joint serial robot.
template <int N>
class Automatic final : public RegressorDerivatives {
public:
    using Lanes = Eigen::Matrix<double, 3 * N, 1>;
    using AD = Eigen::AutoDiffScalar<Lanes>;
    using V3 = Eigen::Matrix<AD, 3, 1>;
    using M3 = Eigen::Matrix<AD, 3, 3>;

    explicit Automatic(const robot::SerialRobotModel& model) : layout_(N, model.config().options) {
        const auto& config = model.config();
        for (int j = 0; j < N; ++j) {
            joints_[static_cast<std::size_t>(j)] = config.joints[static_cast<std::size_t>(j)];
            joints_[static_cast<std::size_t>(j)].axis.normalize();
            coulomb_[static_cast<std::size_t>(j)] = static_cast<std::size_t>(j) < config.joint_coulomb.size() ? config.joint_coulomb[static_cast<std::size_t>(j)]
                                                                                                              : config.options.coulomb;
        }
        gravity_ = config.gravity;
        const auto& base = model.base().base_columns;
        standard_of_base_.assign(base.begin(), base.end());
        standard_count_ = layout_.count();
    }
    DerivativeRoute route() const override { return DerivativeRoute::Automatic; }

    void evaluate(const double* q, const double* qd, const double* qdd, const Eigen::Ref<const Eigen::MatrixXd>& H, const Eigen::VectorXd& x, Eigen::VectorXd& dphi,
                  Eigen::MatrixXd* dtau) const override {
        // The base-parameter weights on their standard columns (every other standard column weighs 0).
        Eigen::Matrix<double, N, Eigen::Dynamic> Hs = Eigen::Matrix<double, N, Eigen::Dynamic>::Zero(N, standard_count_);
        Eigen::VectorXd xs = Eigen::VectorXd::Zero(standard_count_);
        const bool with_phi = H.size() > 0;
        for (std::size_t b = 0; b < standard_of_base_.size(); ++b) {
            if (with_phi) Hs.col(standard_of_base_[b]) = H.col(static_cast<Eigen::Index>(b));
            xs[standard_of_base_[b]] = x[static_cast<Eigen::Index>(b)];
        }
        std::array<LinkState, N> links;
        forward(q, qd, qdd, links);
        AD phi(0.0, Lanes::Zero());
        std::array<AD, N> tau;
        tau.fill(AD(0.0, Lanes::Zero()));
        for (int j = 0; j < N; ++j) {
            const LinkState& link = links[static_cast<std::size_t>(j)];
            const Eigen::Matrix<AD, 6, robot::kInertialKinds> K = wrench_matrix(link);
            const int first = layout_.column(j, ParameterKind::XX);
            // The wrench of link j for the torque's parameters and, per carrying joint i, for H's row i.
            const Eigen::Matrix<AD, 6, 1> f_tau = K * xs.segment<robot::kInertialKinds>(first).template cast<AD>();
            for (int i = j; i >= 0; i = joints_[static_cast<std::size_t>(i)].antecedent) {
                const LinkState& carrier = links[static_cast<std::size_t>(i)];
                Eigen::Matrix<AD, 1, 6> e;
                const V3 z_in_j = link.R0.transpose() * carrier.z0;
                if (joints_[static_cast<std::size_t>(i)].type == JointType::Revolute) {
                    e.template head<3>() = (link.R0.transpose() * carrier.z0.cross(link.o0 - carrier.o0)).transpose();
                    e.template tail<3>() = z_in_j.transpose();
                } else {
                    e.template head<3>() = z_in_j.transpose();
                    e.template tail<3>().setConstant(AD(0.0, Lanes::Zero()));
                }
                tau[static_cast<std::size_t>(i)] += e.dot(f_tau);
                if (with_phi) {
                    const Eigen::Matrix<AD, 6, 1> f_phi = K * Hs.row(i).segment(first, robot::kInertialKinds).transpose().template cast<AD>();
                    phi += e.dot(f_phi);
                }
            }
        }
        dphi.setZero(3 * N);
        if (with_phi) dphi = phi.derivatives();
        Eigen::MatrixXd dt(N, 3 * N);
        for (int i = 0; i < N; ++i) dt.row(i) = tau[static_cast<std::size_t>(i)].derivatives().transpose();
        // Rotor inertia, viscous and Coulomb friction act on their own joint: d/dqdd_j IA, d/dqd_j FV, s'(qd_j) FC.
        for (int j = 0; j < N; ++j) {
            const double slope = coulomb_[static_cast<std::size_t>(j)].slope(qd[j]);
            const int ia = layout_.column(j, ParameterKind::IA), fv = layout_.column(j, ParameterKind::FV), fc = layout_.column(j, ParameterKind::FC);
            if (ia >= 0) {
                dt(j, 2 * N + j) += xs[ia];
                if (with_phi) dphi[2 * N + j] += Hs(j, ia);
            }
            dt(j, N + j) += xs[fv] + slope * xs[fc];
            if (with_phi) dphi[N + j] += Hs(j, fv) + slope * Hs(j, fc);
        }
        if (dtau) *dtau = dt;
    }

private:
    struct LinkState {
        V3 w, wd, vd, o0, z0;
        M3 R0;
    };

    static AD constant(double v) { return AD(v, Lanes::Zero()); }
    static AD lane(double v, int k) { return AD(v, 3 * N, k); }

    static M3 skew(const V3& v) {
        M3 s;
        s << constant(0.0), -v.z(), v.y(), v.z(), constant(0.0), -v.x(), -v.y(), v.x(), constant(0.0);
        return s;
    }

    static Eigen::Matrix<AD, 3, 6> inertia_map(const V3& x) {
        const AD z = constant(0.0);
        Eigen::Matrix<AD, 3, 6> L;
        L << x.x(), x.y(), x.z(), z, z, z,  //
            z, x.x(), z, x.y(), x.z(), z,   //
            z, z, x.x(), z, x.y(), x.z();
        return L;
    }

    static Eigen::Matrix<AD, 6, robot::kInertialKinds> wrench_matrix(const LinkState& link) {
        Eigen::Matrix<AD, 6, robot::kInertialKinds> K;
        K.setConstant(constant(0.0));
        const M3 Sw = skew(link.w);
        K.template block<3, 3>(0, 6) = skew(link.wd) + Sw * Sw;
        K.template block<3, 1>(0, 9) = link.vd;
        K.template block<3, 6>(3, 0) = inertia_map(link.wd) + Sw * inertia_map(link.w);
        K.template block<3, 3>(3, 6) = -skew(link.vd);
        return K;
    }

    void forward(const double* q, const double* qd, const double* qdd, std::array<LinkState, N>& links) const {
        const V3 zero = V3::Constant(constant(0.0));
        const V3 base_vd = (-gravity_).cast<AD>();
        for (int j = 0; j < N; ++j) {
            const ChainJoint& joint = joints_[static_cast<std::size_t>(j)];
            const bool at_base = joint.antecedent < 0;
            const LinkState* parent = at_base ? nullptr : &links[static_cast<std::size_t>(joint.antecedent)];
            const V3 w_a = at_base ? zero : parent->w, wd_a = at_base ? zero : parent->wd, vd_a = at_base ? base_vd : parent->vd;
            const AD qj = lane(q[j], j), qdj = lane(qd[j], N + j), qddj = lane(qdd[j], 2 * N + j);
            const V3 axis = joint.axis.cast<AD>();
            M3 R = joint.rotation.cast<AD>();
            V3 p = joint.position.cast<AD>();
            if (joint.type == JointType::Revolute) {
                // Rodrigues: c I + s [a]x + (1 - c) a a^T.
                const AD c = cos(qj), s = sin(qj);
                const M3 turn = M3::Identity() * c + skew(axis) * s + (axis * axis.transpose()) * (constant(1.0) - c);
                R = R * turn;
            } else {
                p += joint.rotation.cast<AD>() * (axis * qj);
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

    robot::StandardParameterLayout<N> layout_;
    std::array<ChainJoint, N> joints_{};
    std::array<robot::CoulombSign, N> coulomb_{};
    Eigen::Vector3d gravity_;
    std::vector<int> standard_of_base_;
    int standard_count_ = 0;
};

// The adjoint route: per sample one forward Newton-Euler pass, one adjoint pass for phi and, with dtau, one with a
// lane per joint for tau_i = <e_i x^T, Y> (the weights on the standard columns of the base parameters).
template <int N>
class Adjoint final : public RegressorDerivatives {
public:
    using Regression = robot::RneaRegressor<N>;

    explicit Adjoint(const robot::SerialRobotModel& model)
        : regressor_(robot::make_rnea_regressor<N>(model.config())), adjoint_(regressor_), standard_of_base_(model.base().base_columns) {}
    Adjoint(const Adjoint&) = delete;
    Adjoint& operator=(const Adjoint&) = delete;
    DerivativeRoute route() const override { return DerivativeRoute::Adjoint; }

    void evaluate(const double* q, const double* qd, const double* qdd, const Eigen::Ref<const Eigen::MatrixXd>& H, const Eigen::VectorXd& x, Eigen::VectorXd& dphi,
                  Eigen::MatrixXd* dtau) const override {
        typename Regression::Joints vq, vqd, vqdd, gq, gqd, gqdd;
        for (int j = 0; j < N; ++j) vq[j] = q[j], vqd[j] = qd[j], vqdd[j] = qdd[j];
        typename robot::RneaRegressorAdjoint<N>::Links links;
        if (adjoint_.kinematics(vq, vqd, vqdd, links) != robot::RegressorStatus::Ok) {
            throw std::invalid_argument("regressor derivatives: non-finite joint position, velocity or acceleration");
        }
        auto store = [&](Eigen::Ref<Eigen::VectorXd> out) { out << gq, gqd, gqdd; };
        typename Regression::Regressor Hs = Regression::Regressor::Zero();
        dphi.setZero(3 * N);
        if (H.size() > 0) {
            for (std::size_t b = 0; b < standard_of_base_.size(); ++b) Hs.col(standard_of_base_[b]) = H.col(static_cast<Eigen::Index>(b));
            adjoint_.gradient(vqd, links, Hs, gq, gqd, gqdd);
            store(dphi);
        }
        if (!dtau) return;
        typename Regression::Parameters xs = Regression::Parameters::Zero();
        for (std::size_t b = 0; b < standard_of_base_.size(); ++b) xs[standard_of_base_[b]] = x[static_cast<Eigen::Index>(b)];
        typename robot::RneaRegressorAdjoint<N>::Square dq, dqd, dqdd;
        adjoint_.torque_gradient(vqd, links, xs, dq, dqd, dqdd);
        dtau->resize(N, 3 * N);
        *dtau << dq, dqd, dqdd;
    }

private:
    Regression regressor_;
    robot::RneaRegressorAdjoint<N> adjoint_;  // refers to regressor_
    std::vector<int> standard_of_base_;
};

// One of the fixed-size routes for the model's joint count.
template <template <int> class Route, int N = 1>
std::unique_ptr<RegressorDerivatives> make_fixed(const robot::SerialRobotModel& model) {
    if constexpr (N > robot::kMaxSerialJoints) {
        return nullptr;
    } else {
        if (model.joint_count() == N) return std::make_unique<Route<N>>(model);
        return make_fixed<Route, N + 1>(model);
    }
}

}  // namespace

const char* to_string(DerivativeRoute route) {
    switch (route) {
        case DerivativeRoute::Adjoint: return "adjoint";
        case DerivativeRoute::CentralDifferences: return "central";
        case DerivativeRoute::Automatic: return "automatic";
    }
    return "?";
}

std::unique_ptr<RegressorDerivatives> make_regressor_derivatives(const robot::RobotModel& model, DerivativeRoute route) {
    if (const auto* serial = dynamic_cast<const robot::SerialRobotModel*>(&model)) {
        std::unique_ptr<RegressorDerivatives> fixed;
        if (route == DerivativeRoute::Adjoint) fixed = make_fixed<Adjoint>(*serial);
        if (route == DerivativeRoute::Automatic) fixed = make_fixed<Automatic>(*serial);
        if (fixed) return fixed;
    }
    return std::make_unique<CentralDifferences>(model);
}

}  // namespace jacobid::excite
