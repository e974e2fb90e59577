// SPDX-License-Identifier: MIT
// diagnose --export-robot (issue 40; docs/diagnose.md, "Exporting the improved description"): the loop closed in
// files on a simulated 2R whose truth has a Coulomb offset on joint 1 (an effect the description can carry) and
// cogging on joint 2 (one it cannot): the exported description carries the offset, lists the cogging, and
// `identify --robot exported.yaml` finds the injected offset and predicts a held-out log better than the
// description diagnose was given. The references are the simulator's injected values.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "diagnose_test_support.hpp"
#include "robot/robot_description.hpp"

namespace {

using namespace jacobid::test;

constexpr const char* kEffects = "--effect coulomb_offset:joint=1,value=0.2 --effect cogging:joint=2,amplitude=0.15,order=8";

nlohmann::json identify(const std::string& robot, const std::string& log, const std::string& validation) {
    const auto r = run_command(std::string(JACOBID_EXECUTABLE) + " identify --robot " + robot + " --in " + log + " --validate " + validation +
                               " --format json --quiet");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return r.exit_code == 0 ? nlohmann::json::parse(r.out) : nlohmann::json::object();
}

TEST(DiagnoseExport, TheExportedDescriptionIdentifiesTheNamedEffect) {
    const std::string log = scratch("export_log.csv"), validation = scratch("export_val.csv"), exported = scratch("exported.yaml");
    ASSERT_EQ(simulate_log(log, 30, 41, kEffects).exit_code, 0);
    ASSERT_EQ(simulate_log(validation, 20, 42, kEffects).exit_code, 0);
    const auto r = run_command(std::string(JACOBID_EXECUTABLE) + " diagnose --robot " + diagnose_robot_yaml() + " --in " + log +
                               " --export-robot " + exported + " --format json --quiet");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto d = nlohmann::json::parse(r.out);
    ASSERT_TRUE(d.contains("export")) << d.dump();
    EXPECT_EQ(d["export"]["robot"], exported);
    EXPECT_EQ(d["export"]["added"].size(), 1u) << d["export"].dump();
    ASSERT_EQ(d["export"]["not_in_description"].size(), 1u) << d["export"].dump();
    EXPECT_NE(d["export"]["not_in_description"][0].get<std::string>().find("cogging"), std::string::npos);

    // The file is a description load_robot_description reads: the original with the offset switched on.
    const jacobid::robot::RobotDescription e = jacobid::robot::load_robot_description(exported);
    EXPECT_TRUE(e.friction_offset);
    EXPECT_EQ(e.model, "planar2r");
    EXPECT_EQ(e.joints.size(), 2u);

    const nlohmann::json before = identify(diagnose_robot_yaml(), log, validation), after = identify(exported, log, validation);
    ASSERT_TRUE(after.contains("parameters")) << after.dump();
    ASSERT_TRUE(after["parameters"].contains("FOFF1")) << after["parameters"].dump();
    EXPECT_NEAR(after["parameters"]["FOFF1"]["value"].get<double>(), 0.2, 0.04);  // the injected offset, within 20 %
    const double e_before = before["methods"]["jacobi"]["validation"]["relative_error"].get<double>();
    const double e_after = after["methods"]["jacobi"]["validation"]["relative_error"].get<double>();
    EXPECT_LT(e_after, e_before);
    std::printf("diagnose --export-robot: FOFF1 %.4f N.m (injected 0.2); held-out relative error %.2f %% -> %.2f %%\n",
                after["parameters"]["FOFF1"]["value"].get<double>(), 100 * e_before, 100 * e_after);
}

TEST(DiagnoseExport, RefusesToWriteOverItsInput) {
    const std::string log = scratch("export_guard.csv");
    ASSERT_EQ(simulate_log(log, 10, 43, "").exit_code, 0);
    const auto r = run_command(std::string(JACOBID_EXECUTABLE) + " diagnose --robot " + diagnose_robot_yaml() + " --in " + log +
                               " --export-robot " + diagnose_robot_yaml() + " --quiet");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("--export-robot"), std::string::npos) << r.err;
}

}  // namespace
