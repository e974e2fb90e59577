// SPDX-License-Identifier: MIT
// The monitor's model from descriptions that carry friction extensions (the ones `identify --export-robot` writes
// from a `diagnose --export-robot` description): presliding's FDj and coulomb_load's FCLj are not standard
// parameters of the chain, and were refused ("model mdh has no standard parameter 'FD1'") before issue 40's
// export loop. Checked against the description's own numbers.
#include <gtest/gtest.h>

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

TEST(MonitorModel, ReadsPreslidingAndLeavesTheLoadDependentCoulombOutWithANote) {
    const std::string path = write("extended.yaml", ", presliding: dahl, presliding_displacement: 4e-4, coulomb_load: abs",
                                   ", FD1: 0.7, FD2: 0.4, FCL2: 0.05");
    const monitor::MonitorModel m = monitor::load_monitor_model(path, {0.02}, 0.1, 0.001);
    ASSERT_EQ(m.joints(), 2);
    EXPECT_DOUBLE_EQ(m.friction.joint(0).presliding, 0.7);
    EXPECT_DOUBLE_EQ(m.friction.joint(1).presliding, 0.4);
    EXPECT_DOUBLE_EQ(m.friction.joint(0).presliding_displacement, 4e-4);
    EXPECT_DOUBLE_EQ(m.friction.joint(0).coulomb, 3.0);
    EXPECT_DOUBLE_EQ(m.friction.joint(1).viscous, 0.4);
    ASSERT_EQ(m.notes.size(), 1u);
    EXPECT_NE(m.notes[0].find("coulomb_load"), std::string::npos);
    // The rigid body is the description's: at rest, joint 2's gravity torque is g MX2 (the link's first moment along x2).
    robot::JointVector<monitor::kJoints> q = robot::JointVector<monitor::kJoints>::Zero(), g;
    m.terms->gravity(q, g);
    EXPECT_NEAR(std::abs(g[1]), 9.81 * 0.3, 1e-9);
}

}  // namespace
