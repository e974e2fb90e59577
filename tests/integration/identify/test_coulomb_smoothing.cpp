// SPDX-License-Identifier: MIT
// friction alpha: auto on simulated 2R logs whose true Coulomb smoothing differs per joint (alpha 30 on
// joint 1, 300 on joint 2, the simulator's truth): the choice must land on the truth's neighbourhood of the
// candidate grid, and the Coulomb levels must come out closer to the truth than with one fixed alpha.
// Expected values are the simulation's truth, never this code's output.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "identify/friction/coulomb_smoothing.hpp"
#include "run_command.hpp"
#include "simulated_log.hpp"
#include "scratch_directory.hpp"

namespace {

using nlohmann::json;

std::string path(const std::string& name) { return (jacobid::test::scratch_directory() / name).string(); }

jacobid::test::CommandResult jacobid_cli(const std::string& args) { return jacobid::test::run_command(std::string(JACOBID_EXECUTABLE) + " " + args); }

std::string robot_file(const std::string& name, const std::string& alpha) {
    std::ofstream(path(name)) << "model: planar2r\nL1: 0.5\nfriction: {coulomb: smooth, alpha: " << alpha << "}\n";
    return path(name);
}

// Truth: joint 1 with a gentle transition (alpha 30 s/rad), joint 2 a sharp one (300 s/rad).
std::string simulated_log() {
    const std::string log = path("two_alphas.csv");
    if (std::filesystem::exists(log)) return log;
    const auto r = jacobid::test::simulated_log(log, "--quiet --robot " + robot_file("truth.yaml", "[30, 300]") +
                                       " --duration 60 --seed 3 --noise-seed 4 --torque-noise 0.02,0.005");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return log;
}

json identify(const std::string& robot, const std::string& log) {
    const auto r = jacobid_cli("identify --quiet --robot " + robot + " --in " + log + " --format json");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return json::parse(r.out)["methods"]["jacobi"];
}

double error_percent(const json& j, const std::string& name, double truth) { return 100.0 * (j["parameters"][name]["value"].get<double>() - truth) / truth; }

TEST(CoulombSmoothing, AutoFindsEachJointsTransitionAndBeatsOneFixedAlpha) {
    const std::string log = simulated_log();
    const json chosen = identify(robot_file("auto.yaml", "auto"), log);
    ASSERT_TRUE(chosen.contains("coulomb_smoothing")) << chosen.dump();
    const json& c = chosen["coulomb_smoothing"];
    EXPECT_EQ(c["candidates"].size(), jacobid::identify::default_coulomb_candidates().size());
    const double alpha1 = c["joints"][0]["alpha"].get<double>(), alpha2 = c["joints"][1]["alpha"].get<double>();
    EXPECT_TRUE(c["joints"][0]["chosen"].get<bool>());
    EXPECT_TRUE(c["joints"][1]["chosen"].get<bool>());
    // Within one grid step (a factor sqrt 2) of the truth.
    EXPECT_LE(std::abs(std::log(alpha1 / 30.0)), std::log(std::sqrt(2.0)) + 1e-9) << alpha1;
    EXPECT_LE(std::abs(std::log(alpha2 / 300.0)), std::log(std::sqrt(2.0)) + 1e-9) << alpha2;
    // The held-out error of joint 1 is lowest near the truth, not at the grid's ends.
    const json& e1 = c["joints"][0]["heldout_rms"];
    EXPECT_LT(e1[4].get<double>(), e1[0].get<double>());   // 40 vs 10 s/rad
    EXPECT_LT(e1[4].get<double>(), e1[14].get<double>());  // 40 vs 1280 s/rad

    // Paper's Table II truth: FC1 0.431, FC2 0.1268 N.m.
    const json fixed = identify(robot_file("fixed.yaml", "100"), log);
    EXPECT_FALSE(fixed.contains("coulomb_smoothing"));
    EXPECT_LT(std::abs(error_percent(chosen, "FC1", 0.431)), 1.0);
    EXPECT_LT(std::abs(error_percent(chosen, "FC2", 0.1268)), 2.0);
    EXPECT_LT(std::abs(error_percent(chosen, "FC1", 0.431)), std::abs(error_percent(fixed, "FC1", 0.431)));
    EXPECT_LT(std::abs(error_percent(chosen, "FC2", 0.1268)), std::abs(error_percent(fixed, "FC2", 0.1268)));
}

TEST(CoulombSmoothing, GivenPerJointAlphaIsUsedAsIs) {
    const std::string log = simulated_log();
    // The truth's own values: no choice made, the fit is the exact model (friction errors small).
    const json exact = identify(robot_file("exact.yaml", "[30, 300]"), log);
    EXPECT_FALSE(exact.contains("coulomb_smoothing"));
    EXPECT_LT(std::abs(error_percent(exact, "FC1", 0.431)), 1.0);
    EXPECT_LT(std::abs(error_percent(exact, "FC2", 0.1268)), 2.0);
    // Swapped values are a wrong model: the Coulomb levels move away from the truth.
    const json swapped = identify(robot_file("swapped.yaml", "[300, 30]"), log);
    EXPECT_GT(std::abs(error_percent(swapped, "FC1", 0.431)), 2.0 * std::abs(error_percent(exact, "FC1", 0.431)));
}

TEST(CoulombSmoothing, TextReportSaysWhatWasChosen) {
    const std::string log = simulated_log();
    const auto r = jacobid_cli("identify --quiet --robot " + robot_file("auto_text.yaml", "auto") + " --in " + log);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("Coulomb smoothing alpha: auto"), std::string::npos) << r.out;
}

}  // namespace
