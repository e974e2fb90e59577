// SPDX-License-Identifier: MIT
#include <Eigen/Core>
#include <stdexcept>
#include <vector>

#include "excite/serial_derivative_routes.hpp"
#include "jacobid/robot/rnea_regressor_adjoint.hpp"

namespace jacobid::excite {
namespace {

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

// The adjoint for the model's joint count.
template <int N = 1>
std::unique_ptr<RegressorDerivatives> make_fixed(const robot::SerialRobotModel& model) {
    if constexpr (N > robot::kMaxSerialJoints) {
        return nullptr;
    } else {
        if (model.joint_count() == N) return std::make_unique<Adjoint<N>>(model);
        return make_fixed<N + 1>(model);
    }
}

}  // namespace

std::unique_ptr<RegressorDerivatives> make_adjoint_derivatives(const robot::SerialRobotModel& model) { return make_fixed(model); }

}  // namespace jacobid::excite
