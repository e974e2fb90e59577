// SPDX-License-Identifier: MIT
// Sign constraints of base parameters (identify/physical/plausibility.hpp), checked against physics rather than
// against the classification's own rules: base values of many random, physically possible robots
// (positive masses, centres of mass anywhere, inertias positive-definite and obeying the triangle
// inequalities) never go negative where a constraint is claimed, and parameters that can be negative
// on such robots are not claimed.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>
#include <set>

#include "identify/physical/plausibility.hpp"
#include "robot/robot_description.hpp"
#include "robot/serial_robot_model.hpp"
#include "serial_test_support.hpp"

using namespace jacobid;

namespace {

// Standard parameters (XX..FOFF per joint, the model's layout) of a random physically possible robot.
Eigen::VectorXd random_physical_robot(const robot::SerialRobotModel& model, std::mt19937& rng) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    Eigen::VectorXd s = Eigen::VectorXd::Zero(model.standard_parameter_count());
    const int joints = model.joint_count();
    for (int j = 1; j <= joints; ++j) {
        const double m = 0.2 + 10.0 * u(rng);
        const Eigen::Vector3d c(0.6 * u(rng) - 0.3, 0.6 * u(rng) - 0.3, 0.6 * u(rng) - 0.3);
        // Principal moments from a random mass distribution's second moments (always triangle-consistent).
        const Eigen::Vector3d second(0.05 * u(rng), 0.05 * u(rng), 0.05 * u(rng));
        const Eigen::Vector3d principal(m * (second.y() + second.z()), m * (second.x() + second.z()), m * (second.x() + second.y()));
        const Eigen::Matrix3d R = Eigen::Quaterniond::UnitRandom().toRotationMatrix();
        const Eigen::Matrix3d Ic = R * principal.asDiagonal() * R.transpose();
        const Eigen::Matrix3d Io = Ic + m * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
        const auto set = [&](const std::string& kind, double v) {
            const int index = model.standard_index(kind + std::to_string(j));
            if (index >= 0) s[index] = v;
        };
        set("XX", Io(0, 0));
        set("XY", -Io(0, 1));
        set("XZ", -Io(0, 2));
        set("YY", Io(1, 1));
        set("YZ", -Io(1, 2));
        set("ZZ", Io(2, 2));
        set("MX", m * c.x());
        set("MY", m * c.y());
        set("MZ", m * c.z());
        set("M", m);
        set("IA", 0.5 * u(rng));
        set("FV", 2.0 * u(rng));
        set("FC", 2.0 * u(rng));
        set("FOFF", 2.0 * u(rng) - 1.0);
    }
    return s;
}

std::set<std::string> constrained_names(const robot::RobotModel& model) {
    std::set<std::string> out;
    for (const auto& c : identify::sign_constraints(model)) out.insert(model.parameter_names()[static_cast<std::size_t>(c.parameter)]);
    return out;
}

}  // namespace

TEST(Plausibility, ClaimedSignsHoldOnRandomPhysicalRobotsAndFreeOnesDoGoNegative) {
    std::srand(7);  // Quaterniond::UnitRandom uses rand()
    for (const char* file : {"puma560.yaml", "ur5_like.yaml", "scara_rrpr.yaml"}) {
        const auto d = robot::load_robot_description(test::example_robot(file));
        const auto model = robot::make_robot_model(d);
        const auto* serial = dynamic_cast<const robot::SerialRobotModel*>(model.get());
        ASSERT_NE(serial, nullptr);
        const auto constraints = identify::sign_constraints(*model);
        std::mt19937 rng(42);
        std::vector<bool> seen_negative(static_cast<std::size_t>(model->parameter_count()), false);
        for (int trial = 0; trial < 2000; ++trial) {
            const Eigen::VectorXd base = serial->base_values(random_physical_robot(*serial, rng));
            for (const auto& c : constraints) {
                ASSERT_GE(base[c.parameter], -1e-12) << file << ": " << model->parameter_names()[static_cast<std::size_t>(c.parameter)]
                                                     << " claimed non-negative went negative";
            }
            for (int p = 0; p < model->parameter_count(); ++p) seen_negative[static_cast<std::size_t>(p)] = seen_negative[static_cast<std::size_t>(p)] || base[p] < 0.0;
        }
        // Completeness where physics says so: every friction coefficient and rotor inertia is claimed.
        const auto names = constrained_names(*model);
        for (int p = 0; p < model->parameter_count(); ++p) {
            const std::string& n = model->parameter_names()[static_cast<std::size_t>(p)];
            if (n.rfind("FV", 0) == 0 || n.rfind("FC", 0) == 0 || n.rfind("IA", 0) == 0) {
                EXPECT_TRUE(names.count(n)) << file << ": " << n;
            }
            // A parameter that random physical robots drive negative must not be claimed (consistency).
            if (seen_negative[static_cast<std::size_t>(p)]) {
                EXPECT_FALSE(names.count(n)) << file << ": " << n;
            }
        }
    }
}

TEST(Plausibility, PumaRegroupedInertiasOfTheParallelAxisKindAreClaimedDifferencesAreNot) {
    const auto d = robot::load_robot_description(test::example_robot("puma560.yaml"));
    const auto model = robot::make_robot_model(d);
    const auto names = constrained_names(*model);
    // ZZ1R = ZZ1 + IA1 + YY2 + 0.487 MZ2 + 0.0593 M2 + ...: a sum of inertias about axis 1 (parallel axes).
    EXPECT_TRUE(names.count("ZZ1R"));
    EXPECT_TRUE(names.count("ZZ2R"));
    EXPECT_TRUE(names.count("ZZ4R"));  // ZZ4 + YY5
    EXPECT_TRUE(names.count("ZZ6"));
    EXPECT_FALSE(names.count("XX2R"));  // XX2 - YY2 - ...: a difference
    EXPECT_FALSE(names.count("MX2R"));  // a first moment: any sign
    EXPECT_FALSE(names.count("XY2"));
}

TEST(Plausibility, Planar2RAndViolationsAreListedWithTheirStd) {
    const auto model = robot::make_robot_model(robot::default_planar2r_description());
    EXPECT_EQ(constrained_names(*model), (std::set<std::string>{"ZZ1R", "FV1", "FC1", "ZZ2", "FV2", "FC2"}));
    identify::LsSolution s;
    s.names = model->parameter_names();
    const int n = model->parameter_count();
    s.x = Eigen::VectorXd::Constant(n, 0.1);
    s.std_dev = Eigen::VectorXd::Constant(n, 0.01);
    s.rel_std_percent = Eigen::VectorXd::Constant(n, 10.0);
    s.identified.assign(static_cast<std::size_t>(n), true);
    s.x[1] = -0.05;  // FV1 < 0: a violation
    s.x[4] = -0.05;  // MX2 < 0: allowed
    s.x[7] = -0.05;  // FC2 < 0 but not identified: not reported
    s.identified[7] = false;
    const auto v = identify::plausibility_violations(identify::sign_constraints(*model), s);
    ASSERT_EQ(v.size(), 1u);
    EXPECT_EQ(v[0].name, "FV1");
    EXPECT_DOUBLE_EQ(v[0].value, -0.05);
    const std::string text = identify::describe(v[0]);
    EXPECT_NE(text.find("FV1 = -0.05"), std::string::npos) << text;
    EXPECT_NE(text.find("viscous friction"), std::string::npos) << text;
    EXPECT_NE(text.find("more than 2 sigma below 0"), std::string::npos) << text;
}
