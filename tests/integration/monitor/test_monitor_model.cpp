// SPDX-License-Identifier: MIT
// The monitor's model from descriptions that carry friction extensions (the ones `identify --export-robot` writes
// from a `diagnose --export-robot` description): presliding's FDj and coulomb_load's FCLj are not standard
// parameters of the chain, and were refused ("model mdh has no standard parameter 'FD1'") before issue 40's
// export loop; the monitor runs both. Checked against the description's own numbers.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <fstream>
#include <string>

#include "monitor/monitor_model.hpp"
#include "scratch_directory.hpp"

namespace {

using namespace jacobid;

std::string write(const std::string& name, const std::string& friction, const std::string& extra) {
    const std::string path = (test::scratch_directory() / name).string();
    std::ofstream(path) << "model: mdh\ngravity: [0, 0, -9.81]\njoints:\n"
                           "  - {name: j1, sigma: 0, alpha: 0, d: 0, theta: 0, r: 0}\n"
                           "  - {name: j2, sigma: 0, alpha: 1.5707963267948966, d: 0, theta: 0, r: 0}\n"
                           "friction: {coulomb: smooth, alpha: 100" + friction + "}\n"
                           "parameters: {ZZ1: 1.0, M2: 2.0, MX2: 0.3, ZZ2: 0.2, FV1: 0.5, FC1: 3.0, FV2: 0.4, FC2: 2.0" + extra + "}\n";
    return path;
}

TEST(MonitorModel, ReadsPreslidingAndTheLoadDependentCoulombLevel) {
    const std::string path = write("extended.yaml", ", presliding: dahl, presliding_displacement: 4e-4, coulomb_load: abs",
                                   ", FD1: 0.7, FD2: 0.4, FCL2: 0.05");
    const monitor::MonitorModel m = monitor::load_monitor_model(path, {0.02}, 0.1, 0.001);
    ASSERT_EQ(m.joints(), 2);
    EXPECT_DOUBLE_EQ(m.friction.joint(0).presliding, 0.7);
    EXPECT_DOUBLE_EQ(m.friction.joint(1).presliding, 0.4);
    EXPECT_DOUBLE_EQ(m.friction.joint(0).presliding_displacement, 4e-4);
    EXPECT_DOUBLE_EQ(m.friction.joint(0).coulomb, 3.0);
    EXPECT_DOUBLE_EQ(m.friction.joint(1).viscous, 0.4);
    EXPECT_TRUE(m.notes.empty());
    EXPECT_DOUBLE_EQ(m.friction.joint(1).load, 0.05);
    EXPECT_FALSE(m.friction.joint(1).load_square);
    EXPECT_DOUBLE_EQ(m.friction.joint(0).load, 0.0);
    // The rigid body is the description's: at rest, joint 2's gravity torque is g MX2 (the link's first moment along x2).
    using Joints = robot::JointVector<monitor::kJoints>;
    const Joints q = Joints::Zero(), qd = Joints::Zero();
    Joints g;
    m.terms->gravity(q, g);
    EXPECT_NEAR(std::abs(g[1]), 9.81 * 0.3, 1e-9);
    // Standing (0.1 s below 0.02 rad/s at 1 kHz), a joint holds its whole Coulomb level, FC + FCL |g|, and the
    // presliding level beside the model's FD z: + |FD| (1 + |z|), z = 0 here (q never moved).
    robot::JointFriction<monitor::kJoints> friction = m.friction;
    Joints f, band;
    std::array<bool, monitor::kJoints> standing{};
    for (int i = 0; i < 100; ++i) friction.step(q, qd, f, band, standing, &g);
    ASSERT_TRUE(standing[1]);
    EXPECT_NEAR(band[1], 2.0 + 0.05 * 9.81 * 0.3 + 0.4, 1e-9);
    EXPECT_NEAR(band[0], 3.0 + 0.7, 1e-12);
    // Moving at 1 rad/s (smoothed sign 2/pi atan(100)), the load-dependent level adds to the sliding friction.
    Joints moving = Joints::Zero();
    moving[1] = 1.0;
    friction.step(q, moving, f, band, standing, &g);
    const double s = 2.0 / M_PI * std::atan(100.0);
    EXPECT_NEAR(f[1], 0.4 * 1.0 + (2.0 + 0.05 * 9.81 * 0.3) * s, 1e-9);  // FV2 qd + (FC2 + FCL2 |g2|) s(qd); z stays 0 (q still)
}

}  // namespace
