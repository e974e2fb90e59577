// SPDX-License-Identifier: MIT
// friction coulomb_load: abs on simulated logs of a 2R arm in a vertical plane whose truth has Coulomb
// friction growing with the gravity load (FCL1 0.03, FCL2 0.08 N.m per N.m; the simulator applies it through
// the forward dynamics): identify recovers the levels and the Coulomb levels a load-blind model inflates, and
// cuts the validation error on a second log; on data without the effect the levels come out 0 within their
// std. Expected values are the simulation's truth, never this code's output.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "run_command.hpp"
#include "simulated_log.hpp"
#include "scratch_directory.hpp"

namespace {

using nlohmann::json;

std::string path(const std::string& name) { return (jacobid::test::scratch_directory() / name).string(); }

jacobid::test::CommandResult jacobid_cli(const std::string& args) { return jacobid::test::run_command(std::string(JACOBID_EXECUTABLE) + " " + args); }

// The paper's Table II on a vertical plane (gravity along -y of the base), `load` the coulomb_load law.
std::string robot_file(const std::string& name, const std::string& load, const std::string& levels = "") {
    std::ofstream(path(name)) << "model: mdh\ngravity: [0, -9.81, 0]\njoints:\n"
                                 "  - {name: j1, sigma: 0, alpha: 0, d: 0, theta: 0, r: 0}\n"
                                 "  - {name: j2, sigma: 0, alpha: 0, d: 0.5, theta: 0, r: 0}\n"
                                 "friction: {coulomb: smooth, alpha: 100, coulomb_load: "
                              << load
                              << "}\nparameters: {ZZ1: 2.996, M2: 2.0, FV1: 0.248, FC1: 0.431, ZZ2: 0.059, MX2: 0.124, MY2: 0.0019, "
                                 "FV2: 0.0144, FC2: 0.1268"
                              << levels << "}\n";
    return path(name);
}

std::string simulated(const std::string& name, const std::string& robot, const std::string& seeds, const std::string& duration) {
    const std::string log = path(name);
    if (std::filesystem::exists(log)) return log;
    const auto r = jacobid::test::simulated_log(log, "--quiet --robot " + robot + " --duration " + duration + " " + seeds +
                               " --torque-noise 0.02,0.005");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return log;
}

json identify(const std::string& robot, const std::string& log, const std::string& extra = "") {
    const auto r = jacobid_cli("identify --quiet --robot " + robot + " --in " + log + " " + extra + " --format json");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return json::parse(r.out)["methods"]["jacobi"];
}

double value(const json& j, const std::string& name) { return j["parameters"][name]["value"].get<double>(); }
double stdev(const json& j, const std::string& name) { return j["parameters"][name]["std"].get<double>(); }

TEST(LoadFrictionIdentify, IdentifiesTheSimulatedLevelsAndCutsTheValidationError) {
    const std::string truth = robot_file("load_truth.yaml", "abs", ", FCL1: 0.03, FCL2: 0.08");
    const std::string train = simulated("load_train.csv", truth, "--seed 3 --noise-seed 4", "60");
    const std::string test = simulated("load_test.csv", truth, "--seed 7 --noise-seed 8", "30");
    const json load = identify(robot_file("load.yaml", "abs"), train, "--validate " + test);
    const json plain = identify(robot_file("plain.yaml", "none"), train, "--validate " + test);
    EXPECT_FALSE(plain["parameters"].contains("FCL1"));
    EXPECT_NEAR(value(load, "FCL1"), 0.03, 0.03 * 0.03);
    EXPECT_NEAR(value(load, "FCL2"), 0.08, 0.08 * 0.03);
    // A load-blind model puts the loaded friction into the Coulomb levels (truth FC1 0.431, FC2 0.1268 N.m).
    EXPECT_LT(std::abs(value(load, "FC1") - 0.431), 0.1 * std::abs(value(plain, "FC1") - 0.431));
    EXPECT_LT(std::abs(value(load, "FC2") - 0.1268), 0.1 * std::abs(value(plain, "FC2") - 0.1268));
    EXPECT_LT(load["validation"]["relative_error"].get<double>(), 0.5 * plain["validation"]["relative_error"].get<double>());
}

TEST(LoadFrictionIdentify, DataWithoutTheEffectGiveLevelsOfZero) {
    const std::string clean = simulated("load_clean.csv", robot_file("clean_truth.yaml", "none"), "--seed 3 --noise-seed 4", "60");
    const json load = identify(robot_file("load_on_clean.yaml", "abs"), clean);
    for (const char* name : {"FCL1", "FCL2"}) {
        EXPECT_LT(std::abs(value(load, name)), 4.0 * stdev(load, name)) << name << " " << value(load, name) << " +- " << stdev(load, name);
        EXPECT_LT(std::abs(value(load, name)), 1e-3) << name;
    }
}

TEST(LoadFrictionIdentify, ARobotGravityNeverLoadsIsRefusedOnOneLine) {
    std::ofstream(path("flat.yaml")) << "model: planar2r\nfriction: {coulomb_load: abs}\n";
    const std::string clean = simulated("load_clean.csv", robot_file("clean_truth.yaml", "none"), "--seed 3 --noise-seed 4", "60");
    const auto r = jacobid_cli("identify --quiet --robot " + path("flat.yaml") + " --in " + clean);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("coulomb_load"), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

}  // namespace
