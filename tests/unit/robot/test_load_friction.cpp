// SPDX-License-Identifier: MIT
// friction coulomb_load (robot/load_friction_model.hpp) on a 2R arm in a VERTICAL plane (MDH, gravity along
// -y of the base): the FCLj columns against the gravity torque written out by hand from the potential
// energy, the direct inverse dynamics and the articulated-body route against the regressor and the
// inertia-matrix route, joints gravity never loads, and the description's errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "core/errors.hpp"
#include "robot/load_friction_model.hpp"
#include "robot/robot_description.hpp"

namespace {

using namespace jacobid;

// Table II of the paper on a vertical plane: link 2's first moments MX2, MY2 and mass M2 at d2 = 0.5 m.
constexpr double kM2 = 2.0, kMX2 = 0.124, kMY2 = 0.0019, kD2 = 0.5, kG = 9.81;

std::string vertical_2r(const std::string& law, const std::string& gravity = "[0, -9.81, 0]", const std::string& extra = "") {
    return "model: mdh\ngravity: " + gravity +
           "\njoints:\n  - {name: j1, sigma: 0, alpha: 0, d: 0, theta: 0, r: 0}\n  - {name: j2, sigma: 0, alpha: 0, d: 0.5, theta: 0, r: 0}\n"
           "friction: {coulomb: smooth, alpha: 100, coulomb_load: " +
           law + "}\nparameters: {ZZ1: 2.996, M2: 2.0, FV1: 0.248, FC1: 0.431, ZZ2: 0.059, MX2: 0.124, MY2: 0.0019, FV2: 0.0144, FC2: 0.1268" +
           extra + "}\n";
}

// dU/dq of U = g (M2 d2 sin q1 + MX2 sin(q1 + q2) + MY2 cos(q1 + q2)), the height of link 2's centre of mass
// times its weight (link 1 carries no first moment here).
std::vector<double> gravity_by_hand(double q1, double q2) {
    const double c12 = std::cos(q1 + q2), s12 = std::sin(q1 + q2);
    const double t2 = kG * (kMX2 * c12 - kMY2 * s12);
    return {kG * kM2 * kD2 * std::cos(q1) + t2, t2};
}

double smooth_sign(double v) { return 2.0 / M_PI * std::atan(100.0 * v); }

TEST(LoadFriction, ColumnsAreTheHandGravityTorqueTimesTheCoulombSign) {
    for (const std::string law : {"abs", "square"}) {
        const auto d = robot::parse_robot_description(vertical_2r(law, "[0, -9.81, 0]", ", FCL1: 0.03, FCL2: 0.08"), "v.yaml");
        const auto model = robot::make_robot_model(d);
        const int p = model->parameter_count();
        ASSERT_EQ(model->parameter_names()[static_cast<std::size_t>(p - 2)], "FCL1");
        ASSERT_EQ(model->parameter_names()[static_cast<std::size_t>(p - 1)], "FCL2");
        Eigen::MatrixXd D(2, p);
        for (const auto& [q1, q2, v1, v2] : std::vector<std::array<double, 4>>{{0.3, -1.1, 0.2, -0.01}, {2.0, 0.4, -0.5, 0.003}, {-1.4, 2.9, 0.0, 1.0}}) {
            const double q[2] = {q1, q2}, qd[2] = {v1, v2}, qdd[2] = {0.7, -0.3};
            model->regressor(q, qd, qdd, D);
            const auto g = gravity_by_hand(q1, q2);
            auto factor = [&](double t) { return law == "abs" ? std::abs(t) : t * t; };
            EXPECT_NEAR(D(0, p - 2), factor(g[0]) * smooth_sign(v1), 1e-12 * (1 + factor(g[0]))) << law;
            EXPECT_NEAR(D(1, p - 1), factor(g[1]) * smooth_sign(v2), 1e-12 * (1 + factor(g[1]))) << law;
            EXPECT_EQ(D(1, p - 2), 0.0);
            EXPECT_EQ(D(0, p - 1), 0.0);
            // The Coulomb evaluation lists and fills the same columns.
            Eigen::MatrixXd C = Eigen::MatrixXd::Zero(2, p);
            model->coulomb_columns(q, qd, qdd, C);
            EXPECT_EQ(C(0, p - 2), D(0, p - 2));
            EXPECT_EQ(C(1, p - 1), D(1, p - 1));
        }
        const std::vector<int> coulomb = model->coulomb_column_indices();
        EXPECT_NE(std::find(coulomb.begin(), coulomb.end(), p - 2), coulomb.end());
        EXPECT_NE(std::find(coulomb.begin(), coulomb.end(), p - 1), coulomb.end());
    }
}

TEST(LoadFriction, DirectRoutesAgreeWithTheRegressorAndTheInertiaMatrix) {
    const auto d = robot::parse_robot_description(vertical_2r("abs", "[0, -9.81, 0]", ", FCL1: 0.03, FCL2: 0.08"), "v.yaml");
    const auto model = robot::make_robot_model(d);
    const Eigen::VectorXd x = robot::true_parameters(d, *model);
    EXPECT_DOUBLE_EQ(x[model->parameter_index("FCL1")], 0.03);
    EXPECT_DOUBLE_EQ(x[model->parameter_index("FCL2")], 0.08);
    const double q[2] = {0.9, -0.4}, qd[2] = {0.3, -0.02}, qdd[2] = {1.5, -2.0};
    Eigen::MatrixXd D(2, model->parameter_count());
    model->regressor(q, qd, qdd, D);
    const Eigen::VectorXd by_regressor = D * x;
    double tau[2];
    ASSERT_TRUE(model->inverse_dynamics(q, qd, qdd, x, tau));
    EXPECT_NEAR(tau[0], by_regressor[0], 1e-12);
    EXPECT_NEAR(tau[1], by_regressor[1], 1e-12);
    robot::ForwardDynamics direct(*model, x, robot::ForwardDynamicsSolver::articulated_body);
    robot::ForwardDynamics matrix(*model, x, robot::ForwardDynamicsSolver::inertia_matrix);
    ASSERT_EQ(direct.solver(), robot::ForwardDynamicsSolver::articulated_body);
    double a[2], b[2];
    ASSERT_TRUE(direct.accelerations(q, qd, tau, a));
    ASSERT_TRUE(matrix.accelerations(q, qd, tau, b));
    EXPECT_NEAR(a[0], qdd[0], 1e-10);
    EXPECT_NEAR(a[1], qdd[1], 1e-10);
    EXPECT_NEAR(b[0], qdd[0], 1e-10);
    EXPECT_NEAR(b[1], qdd[1], 1e-10);
}

TEST(LoadFriction, AJointGravityNeverLoadsHasNoColumn) {
    // Gravity along the first axis (z): joint 1 turns about it and carries no weight; here joint 2 does not
    // either (its axis is parallel), so nothing is loaded: refused by name.
    try {
        robot::make_robot_model(robot::parse_robot_description(vertical_2r("abs", "[0, 0, -9.81]"), "flat.yaml"));
        FAIL() << "a robot in a horizontal plane was given load-dependent friction";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("coulomb_load"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("flat.yaml"), std::string::npos) << e.what();
    }
    // Gravity along x of a chain whose joint 1 is vertical and joint 2 horizontal (alpha2 = pi/2): only FCL2.
    const std::string tilted =
        "model: mdh\ngravity: [0, 0, -9.81]\njoints:\n  - {name: j1, sigma: 0, alpha: 0, d: 0, theta: 0, r: 0}\n"
        "  - {name: j2, sigma: 0, alpha: 1.5707963267948966, d: 0.3, theta: 0, r: 0}\n"
        "friction: {coulomb: smooth, alpha: 100, coulomb_load: abs}\nparameters: {M2: 2.0, MX2: 0.3, ZZ2: 0.1, ZZ1: 1.0}\n";
    const auto d = robot::parse_robot_description(tilted, "t.yaml");
    const auto model = robot::make_robot_model(d);
    EXPECT_LT(model->parameter_index("FCL1"), 0);
    EXPECT_GE(model->parameter_index("FCL2"), 0);
    auto with_level = d;
    with_level.parameters.emplace_back("FCL1", 0.1);
    EXPECT_THROW(robot::true_parameters(with_level, *model), InputError);
}

TEST(LoadFriction, DescriptionKeysAndRoundTrip) {
    EXPECT_THROW(robot::parse_robot_description(vertical_2r("linear"), "v.yaml"), InputError);
    // FCLj without coulomb_load is an unknown parameter.
    EXPECT_THROW(robot::parse_robot_description(vertical_2r("none", "[0, -9.81, 0]", ", FCL1: 0.1"), "v.yaml"), InputError);
    const auto d = robot::parse_robot_description(vertical_2r("square", "[0, -9.81, 0]", ", FCL2: 0.05"), "v.yaml");
    EXPECT_EQ(d.coulomb_load, robot::CoulombLoad::square);
    const auto again = robot::parse_robot_description(robot::to_yaml(d), "again.yaml");
    EXPECT_EQ(again.coulomb_load, robot::CoulombLoad::square);
    EXPECT_EQ(robot::true_parameters(again, *robot::make_robot_model(again)), robot::true_parameters(d, *robot::make_robot_model(d)));
    EXPECT_EQ(robot::parse_robot_description(vertical_2r("none"), "v.yaml").coulomb_load, robot::CoulombLoad::none);
}

}  // namespace
