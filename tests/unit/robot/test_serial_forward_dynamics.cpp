// SPDX-License-Identifier: MIT
// The simulator's forward dynamics of a serial robot through the direct Newton-Euler route
// (SerialRobotModel::inverse_dynamics) gives the same accelerations as the generic regressor route
// (a wrapper that hides the fast path), and closes the loop: torques(q, qd, accelerations(tau)) = tau.
#include <gtest/gtest.h>

#include <random>

#include "serial_test_support.hpp"

namespace {

using namespace jacobid;

// The same model without the direct route: ForwardDynamics falls back to regressor columns.
class RegressorOnly final : public robot::RobotModel {
public:
    explicit RegressorOnly(const robot::RobotModel& inner) : inner_(inner) {}
    std::string model_name() const override { return inner_.model_name(); }
    int joint_count() const override { return inner_.joint_count(); }
    int parameter_count() const override { return inner_.parameter_count(); }
    const std::vector<std::string>& parameter_names() const override { return inner_.parameter_names(); }
    void regressor(const double* q, const double* qd, const double* qdd, Eigen::Ref<Eigen::MatrixXd> D) const override {
        inner_.regressor(q, qd, qdd, D);
    }

private:
    const robot::RobotModel& inner_;
};

TEST(SerialForwardDynamics, DirectRouteEqualsRegressorRoute) {
    const auto d = robot::load_robot_description(test::example_robot("puma560.yaml"));
    const auto model = robot::make_robot_model(d);
    const RegressorOnly slow_model(*model);
    const Eigen::VectorXd x = robot::true_parameters(d, *model);
    robot::ForwardDynamics fast(*model, x), slow(slow_model, x);
    std::mt19937 rng(4);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (int trial = 0; trial < 50; ++trial) {
        double q[6], qd[6], tau[6], a_fast[6], a_slow[6], back[6];
        for (int j = 0; j < 6; ++j) q[j] = 2.5 * u(rng), qd[j] = u(rng), tau[j] = 20 * u(rng);
        const Eigen::MatrixXd M = fast.inertia(q);
        EXPECT_LT((M - M.transpose()).cwiseAbs().maxCoeff(), 1e-12);
        EXPECT_GT(M.llt().matrixL().toDenseMatrix().diagonal().minCoeff(), 0.0);
        fast.accelerations(q, qd, tau, a_fast);
        slow.accelerations(q, qd, tau, a_slow);
        fast.torques(q, qd, a_fast, back);
        for (int j = 0; j < 6; ++j) {
            EXPECT_NEAR(a_fast[j], a_slow[j], 1e-9 * std::max(1.0, std::abs(a_slow[j])));
            EXPECT_NEAR(back[j], tau[j], 1e-9);
        }
    }
}

}  // namespace
