// SPDX-License-Identifier: MIT
// The simulator's truth model (sim/augmented_model.hpp: nominal model + hidden-effect columns) through its
// fast routes: the direct inverse dynamics against the regressor times the parameters, the articulated-body
// forward dynamics against the inertia-matrix route and against the accelerations the torque was made from,
// and rotor_inertia (a term that changes the inertia matrix) falling back to the inertia matrix.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "robot/load_friction_model.hpp"
#include "robot/robot_description.hpp"
#include "sim/augmented_model.hpp"
#include "sim/effect_spec.hpp"

namespace {

using namespace jacobid;

// A 2R arm in a vertical plane, so that coulomb_load has a gravity load to act on.
const char* kVertical2r =
    "model: mdh\ngravity: [0, -9.81, 0]\njoints:\n  - {name: j1, sigma: 0, alpha: 0, d: 0, theta: 0, r: 0}\n"
    "  - {name: j2, sigma: 0, alpha: 0, d: 0.5, theta: 0, r: 0}\nfriction: {coulomb: smooth, alpha: 100}\n"
    "parameters: {ZZ1: 2.996, M2: 2.0, FV1: 0.248, FC1: 0.431, ZZ2: 0.059, MX2: 0.124, MY2: 0.0019, FV2: 0.0144, FC2: 0.1268}\n";

struct Truth {
    robot::RobotDescription description;
    std::unique_ptr<robot::RobotModel> nominal;
    std::unique_ptr<sim::AugmentedModel> model;
    Eigen::VectorXd x;
};

// The truth the simulator builds for these --effect tokens (cli/simulate_command.cpp does the same).
Truth truth_with(const std::vector<std::string>& tokens) {
    Truth t;
    t.description = robot::parse_robot_description(kVertical2r, "vertical.yaml");
    t.nominal = robot::make_robot_model(t.description);
    const Eigen::VectorXd x = robot::true_parameters(t.description, *t.nominal);
    sim::EffectContext context{t.nominal->model_name(), 2, t.description.coulomb, robot::joint_coulomb_signs(t.description)};
    context.load = robot::gravity_load_reference(t.description);
    std::vector<sim::EffectTerm> terms;
    std::vector<Eigen::VectorXd> coefficients;
    for (const auto& token : tokens) {
        const sim::EffectSpec spec = sim::parse_effect(token, 2);
        terms.push_back(sim::term_of(spec));
        coefficients.push_back(sim::injected_coefficients(spec, *t.nominal, x));
    }
    t.model = std::make_unique<sim::AugmentedModel>(*t.nominal, context, terms);
    t.x.resize(t.model->parameter_count());
    t.x.head(t.nominal->parameter_count()) = x;
    for (std::size_t k = 0; k < terms.size(); ++k) t.x.segment(t.model->term_column(k), terms[k].column_count()) = coefficients[k];
    return t;
}

void expect_routes_agree(const Truth& t, robot::ForwardDynamicsSolver expected_solver) {
    const double q[2] = {0.9, -0.4}, qd[2] = {0.3, -0.02}, qdd[2] = {1.5, -2.0};
    Eigen::MatrixXd D(2, t.model->parameter_count());
    t.model->regressor(q, qd, qdd, D);
    const Eigen::VectorXd by_regressor = D * t.x;
    double tau[2];
    ASSERT_TRUE(t.model->inverse_dynamics(q, qd, qdd, t.x, tau));
    EXPECT_NEAR(tau[0], by_regressor[0], 1e-12);
    EXPECT_NEAR(tau[1], by_regressor[1], 1e-12);
    robot::ForwardDynamics fast(*t.model, t.x, robot::ForwardDynamicsSolver::articulated_body);
    robot::ForwardDynamics matrix(*t.model, t.x, robot::ForwardDynamicsSolver::inertia_matrix);
    EXPECT_EQ(fast.solver(), expected_solver);
    double a[2], b[2];
    ASSERT_TRUE(fast.accelerations(q, qd, by_regressor.data(), a));
    ASSERT_TRUE(matrix.accelerations(q, qd, by_regressor.data(), b));
    for (int j = 0; j < 2; ++j) {
        EXPECT_NEAR(a[j], qdd[j], 1e-10) << "joint " << j + 1;
        EXPECT_NEAR(b[j], qdd[j], 1e-10) << "joint " << j + 1;
    }
}

TEST(AugmentedDynamics, EffectsOfStateAloneKeepTheArticulatedBodyRoute) {
    const Truth t = truth_with({"coulomb_offset:joint=1,value=0.05", "coulomb_asymmetry:joint=2,value=0.02",
                                "stribeck:joint=1,value=0.1,velocity=0.05", "viscous_nonlinear:joint=2,value=0.03",
                                "cogging:joint=1,amplitude=0.04,order=6,phase=30", "coulomb_smoothing:joint=2,value=0.05,alpha=20",
                                "coulomb_load:joint=2,value=0.08"});
    // The effects change the torque: a test of routes that ignored them would pass on the nominal model alone.
    const double q[2] = {0.9, -0.4}, qd[2] = {0.3, -0.02}, qdd[2] = {1.5, -2.0};
    Eigen::MatrixXd D(2, t.model->parameter_count());
    t.model->regressor(q, qd, qdd, D);
    Eigen::MatrixXd N(2, t.nominal->parameter_count());
    t.nominal->regressor(q, qd, qdd, N);
    const Eigen::VectorXd effect = D * t.x - N * t.x.head(t.nominal->parameter_count());
    EXPECT_GT(effect.cwiseAbs().minCoeff(), 0.01);
    expect_routes_agree(t, robot::ForwardDynamicsSolver::articulated_body);
}

TEST(AugmentedDynamics, RotorInertiaFallsBackToTheInertiaMatrix) {
    expect_routes_agree(truth_with({"rotor_inertia:joint=2,value=0.02", "coulomb_offset:joint=1,value=0.05"}),
                        robot::ForwardDynamicsSolver::inertia_matrix);
}

}  // namespace
