// SPDX-License-Identifier: MIT
// Static validation (identify/validation/static_validation.hpp) of a vertical 2R arm holding poses: the model's
// prediction at rest is checked against the gravity torques written out by hand from the potential energy
// V = g (m1 c1 sin q1 + m2 (L1 sin q1 + c2 sin(q1 + q2))), and a known torque offset in the "measured"
// log must come out as the error, classified against the Coulomb band.
#include <gtest/gtest.h>

#include <cmath>

#include "identify/validation/static_validation.hpp"
#include "robot/robot_description.hpp"

using namespace jacobid;

namespace {

constexpr double kG = 9.81, kL1 = 0.6, kM1 = 3.0, kC1 = 0.25, kM2 = 2.0, kC2 = 0.3, kFc = 0.4;

const char* kVerticalArm = R"(model: mdh
gravity: [0, -9.81, 0]
joints:
  - {sigma: 0}
  - {sigma: 0, d: 0.6}
friction: {coulomb: smooth, alpha: 100}
parameters: {M1: 3.0, MX1: 0.75, ZZ1: 0.3, M2: 2.0, MX2: 0.6, ZZ2: 0.2, FV1: 0.1, FC1: 0.4, FV2: 0.1, FC2: 0.4}
)";

}  // namespace

TEST(StaticValidation, GravityAtRestMatchesTheHandWrittenTorquesAndAnOffsetIsTheError) {
    const auto d = robot::parse_robot_description(kVerticalArm, "arm.yaml");
    const auto model = robot::make_robot_model(d);
    const Eigen::VectorXd x = robot::true_parameters(d, *model);
    const double q1 = 0.4, q2 = -1.1;
    const double tau1 = kG * (kM1 * kC1 + kM2 * kL1) * std::cos(q1) + kG * kM2 * kC2 * std::cos(q1 + q2);
    const double tau2 = kG * kM2 * kC2 * std::cos(q1 + q2);
    const double offset1 = 0.3, offset2 = -0.9;  // inside, outside the +-0.4 N.m Coulomb band
    const std::size_t n = 500;
    std::vector<double> qa(n, q1), qb(n, q2), ta(n), tb(n);
    for (std::size_t k = 0; k < n; ++k) {
        // Encoder flicker of one count and torque noise that averages out.
        qa[k] += (k % 2 ? 1e-4 : 0.0);
        ta[k] = tau1 + offset1 + (k % 2 ? 0.05 : -0.05);
        tb[k] = tau2 + offset2;
    }
    identify::LogColumns log;
    log.source = "pose.csv";
    log.sample_period = 0.01;
    log.q = {&qa, &qb};
    log.tau = {&ta, &tb};
    EXPECT_TRUE(identify::is_static(log, 1e-3));
    EXPECT_FALSE(identify::is_static(log, 1e-5));
    const auto r = identify::validate_static(*model, log, x);
    ASSERT_EQ(r.joints.size(), 2u);
    EXPECT_NEAR(r.pose[0], q1 + 0.5e-4, 1e-12);
    EXPECT_NEAR(r.joints[0].predicted, kG * (kM1 * kC1 + kM2 * kL1) * std::cos(q1 + 0.0) + kG * kM2 * kC2 * std::cos(q1 + q2), 5e-3);
    EXPECT_NEAR(r.joints[1].predicted, tau2, 1e-3);
    EXPECT_NEAR(r.joints[0].error, offset1, 5e-3);
    EXPECT_NEAR(r.joints[1].error, offset2, 1e-3);
    EXPECT_NEAR(r.joints[0].measured_std, 0.05, 1e-3);
    EXPECT_DOUBLE_EQ(r.joints[0].coulomb, kFc);
    EXPECT_TRUE(r.joints[0].within_friction);
    EXPECT_FALSE(r.joints[1].within_friction);
}
