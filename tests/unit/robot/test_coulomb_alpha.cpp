// SPDX-License-Identifier: MIT
// Per-joint Coulomb smoothing: `friction: {alpha: auto | number | [one per joint]}` in robot descriptions,
// and the regressors' FC columns, checked against 2/pi atan(alpha qd) written out here.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "core/errors.hpp"
#include "jacobid/robot/planar2r.hpp"
#include "robot/robot_description.hpp"
#include "serial_test_support.hpp"

namespace {

using namespace jacobid;

double smooth_sign(double alpha, double v) { return 2.0 / M_PI * std::atan(alpha * v); }

std::string error_of(const std::string& yaml) { return test::description_error_of(yaml); }

TEST(CoulombAlpha, AutoIsTheDefaultANumberOrAListFixesIt) {
    EXPECT_TRUE(robot::parse_robot_description("model: planar2r\n", "r.yaml").coulomb_alpha_auto);
    EXPECT_TRUE(robot::parse_robot_description("model: planar2r\nfriction: {alpha: auto}\n", "r.yaml").coulomb_alpha_auto);
    const auto one = robot::parse_robot_description("model: planar2r\nfriction: {alpha: 50}\n", "r.yaml");
    EXPECT_FALSE(one.coulomb_alpha_auto);
    EXPECT_EQ(one.coulomb.alpha, 50.0);
    EXPECT_TRUE(one.coulomb_alpha.empty());
    const auto list = robot::parse_robot_description("model: planar2r\nfriction: {alpha: [30, 300]}\n", "r.yaml");
    EXPECT_FALSE(list.coulomb_alpha_auto);
    EXPECT_EQ(list.coulomb_alpha, (std::vector<double>{30.0, 300.0}));
    const auto signs = robot::joint_coulomb_signs(list);
    ASSERT_EQ(signs.size(), 2u);
    EXPECT_EQ(signs[0].alpha, 30.0);
    EXPECT_EQ(signs[1].alpha, 300.0);
}

TEST(CoulombAlpha, BadValuesNameTheKey) {
    EXPECT_NE(error_of("model: planar2r\nfriction: {alpha: [30, 300, 3]}\n").find("list of 2 numbers"), std::string::npos);
    EXPECT_NE(error_of("model: planar2r\nfriction: {alpha: -1}\n").find("friction.alpha: must be > 0"), std::string::npos);
    EXPECT_NE(error_of("model: planar2r\nfriction: {alpha: [30, 0]}\n").find("must be > 0"), std::string::npos);
    EXPECT_NE(error_of("model: planar2r\nfriction: {alpha: fast}\n").find("friction.alpha"), std::string::npos);
    EXPECT_NE(error_of("model: planar2r\nfriction: {alpha: {a: 1}}\n").find("expected auto, a number or a list"), std::string::npos);
}

TEST(CoulombAlpha, RoundTripsThroughToYaml) {
    for (const char* alpha : {"auto", "40", "[30, 300]"}) {
        const auto d = robot::parse_robot_description(std::string("model: planar2r\nfriction: {alpha: ") + alpha + "}\n", "r.yaml");
        const auto again = robot::parse_robot_description(robot::to_yaml(d), "again.yaml");
        EXPECT_EQ(again.coulomb_alpha_auto, d.coulomb_alpha_auto) << alpha;
        EXPECT_EQ(again.coulomb.alpha, d.coulomb.alpha) << alpha;
        EXPECT_EQ(again.coulomb_alpha, d.coulomb_alpha) << alpha;
    }
}

TEST(CoulombAlpha, Planar2RColumnsUseEachJointsAlpha) {
    robot::Planar2RConfig config;
    config.coulomb = {robot::CoulombModel::SmoothAtan, 100.0};
    robot::Planar2R model(config);
    model.set_coulomb(1, {robot::CoulombModel::SmoothAtan, 7.0});
    robot::Planar2R::Regressor D;
    const robot::Planar2R::Joints q(0.3, -0.4), qd(0.011, -0.023), qdd(0.5, 0.2);
    model.regressor(q, qd, qdd, D);
    using P = robot::Planar2R::Parameter;
    EXPECT_DOUBLE_EQ(D(0, model.column(P::FC1)), smooth_sign(100.0, 0.011));
    EXPECT_DOUBLE_EQ(D(1, model.column(P::FC2)), smooth_sign(7.0, -0.023));
}

TEST(CoulombAlpha, SerialModelColumnsUseEachJointsAlpha) {
    auto d = robot::load_robot_description(test::example_robot("planar2r_mdh.yaml"));
    d.coulomb.model = robot::CoulombModel::SmoothAtan;
    d.coulomb_alpha = {15.0, 600.0};
    const auto model = robot::make_robot_model(d);
    const double q[2] = {0.2, 0.7}, qd[2] = {-0.004, 0.002}, qdd[2] = {0.1, -0.3};
    Eigen::MatrixXd D(2, model->parameter_count());
    model->regressor(q, qd, qdd, D);
    const int fc1 = model->parameter_index("FC1"), fc2 = model->parameter_index("FC2");
    ASSERT_GE(fc1, 0);
    ASSERT_GE(fc2, 0);
    EXPECT_DOUBLE_EQ(D(0, fc1), smooth_sign(15.0, -0.004));
    EXPECT_DOUBLE_EQ(D(1, fc2), smooth_sign(600.0, 0.002));
    EXPECT_EQ(D(1, fc1), 0.0);
    EXPECT_EQ(D(0, fc2), 0.0);
}

// RobotModel::coulomb_columns (the identification's second pass on the Coulomb velocity): the serial model
// computes the FCj columns alone; they must be the whole regressor's FCj columns, for 6-axis arms with
// per-joint alphas and through the presliding wrapper, and the 2R's sign function written out.
TEST(CoulombAlpha, CoulombColumnsAloneAreTheRegressorsColumns) {
    for (const char* name : {"puma560.yaml", "ur5_like.yaml", "planar2r_mdh.yaml"}) {
        auto d = robot::load_robot_description(test::example_robot(name));
        d.coulomb.model = robot::CoulombModel::SmoothAtan;
        d.coulomb_alpha.clear();
        for (std::size_t j = 0; j < d.joints.size(); ++j) d.coulomb_alpha.push_back(10.0 * static_cast<double>(j + 1));
        for (const bool presliding : {false, true}) {
            d.presliding = presliding;
            const auto model = robot::make_robot_model(d);
            const int n = model->joint_count(), p = model->parameter_count();
            std::vector<double> q(static_cast<std::size_t>(n)), qd(q), qdd(q);
            for (int k = 0; k < 20; ++k) {
                for (int j = 0; j < n; ++j) {
                    q[static_cast<std::size_t>(j)] = std::sin(0.7 * k + j);
                    qd[static_cast<std::size_t>(j)] = 0.05 * std::cos(1.3 * k + 2 * j);
                    qdd[static_cast<std::size_t>(j)] = std::sin(0.4 * k - j);
                }
                Eigen::MatrixXd full(n, p), alone = Eigen::MatrixXd::Constant(n, p, 7.0);
                model->regressor(q.data(), qd.data(), qdd.data(), full);
                model->coulomb_columns(q.data(), qd.data(), qdd.data(), alone);
                int found = 0;
                for (int j = 0; j < n; ++j) {
                    const int fc = model->parameter_index("FC" + std::to_string(j + 1));
                    if (fc < 0) continue;
                    ++found;
                    EXPECT_EQ(alone.col(fc), full.col(fc)) << name << " FC" << j + 1;
                    EXPECT_DOUBLE_EQ(full(j, fc), smooth_sign(10.0 * (j + 1), qd[static_cast<std::size_t>(j)])) << name;
                }
                EXPECT_EQ(found, n) << name << ": every joint has its Coulomb column";
            }
        }
    }
}

}  // namespace
