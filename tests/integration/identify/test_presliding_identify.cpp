// SPDX-License-Identifier: MIT
// friction presliding: dahl on a simulated 2R log whose truth has presliding friction (FD1 0.3, FD2 0.1 N.m,
// x_p 5e-4 rad, the simulator integrating the Dahl state along the true positions): identify with
// presliding_displacement auto recovers the levels, keeps the Coulomb levels near the truth that a
// memory-free model inflates, and cuts the validation error on a second simulated log. Expected values are
// the simulation's truth, never this code's output.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "robot/robot_description.hpp"
#include "run_command.hpp"
#include "simulated_log.hpp"
#include "scratch_directory.hpp"

namespace {

using nlohmann::json;

std::string path(const std::string& name) { return (jacobid::test::scratch_directory() / name).string(); }

jacobid::test::CommandResult jacobid_cli(const std::string& args) { return jacobid::test::run_command(std::string(JACOBID_EXECUTABLE) + " " + args); }

std::string robot_file(const std::string& name, const std::string& friction, const std::string& extra = "") {
    std::ofstream(path(name)) << "model: planar2r\nL1: 0.5\nfriction: {coulomb: smooth, alpha: 100" << friction << "}\n" << extra;
    return path(name);
}

std::string simulated(const std::string& name, const std::string& seeds, const std::string& duration) {
    const std::string log = path(name);
    if (std::filesystem::exists(log)) return log;
    const std::string truth = robot_file("truth.yaml", ", presliding: dahl, presliding_displacement: 5e-4", "parameters: {FD1: 0.3, FD2: 0.1}\n");
    const auto r = jacobid::test::simulated_log(log, "--quiet --robot " + truth + " --duration " + duration + " " + seeds +
                               " --torque-noise 0.02,0.005");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return log;
}

json identify(const std::string& robot, const std::string& log, const std::string& validate) {
    const auto r = jacobid_cli("identify --quiet --robot " + robot + " --in " + log + " --validate " + validate + " --format json");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return json::parse(r.out)["methods"]["jacobi"];
}

double value(const json& j, const std::string& name) { return j["parameters"][name]["value"].get<double>(); }

TEST(PreslidingFriction, IdentifiesTheSimulatedLevelsAndCutsTheValidationError) {
    const std::string train = simulated("presliding_train.csv", "--seed 3 --noise-seed 4", "60");
    const std::string test = simulated("presliding_test.csv", "--seed 7 --noise-seed 8", "30");
    const json dahl = identify(robot_file("dahl.yaml", ", presliding: dahl"), train, test);
    const json plain = identify(robot_file("plain.yaml", ""), train, test);
    ASSERT_TRUE(dahl.contains("presliding_displacement")) << dahl.dump();
    EXPECT_FALSE(plain.contains("presliding_displacement"));
    // Levels within 20 % of the truth (the play operator, two encoder steps wide, delays the state slightly).
    EXPECT_NEAR(value(dahl, "FD1"), 0.3, 0.06);
    EXPECT_NEAR(value(dahl, "FD2"), 0.1, 0.02);
    // x_p chosen within a factor 2.5 of the truth, never at the grid's ends.
    for (int j = 0; j < 2; ++j) {
        const double xp = dahl["presliding_displacement"]["joints"][j]["displacement"].get<double>();
        EXPECT_LT(std::abs(std::log(xp / 5e-4)), std::log(2.5)) << "joint " << j + 1 << ": " << xp;
    }
    // Without memory the Coulomb levels absorb the held friction (truth FC1 0.431, FC2 0.1268 N.m).
    EXPECT_LT(std::abs(value(dahl, "FC1") - 0.431), 0.5 * std::abs(value(plain, "FC1") - 0.431));
    EXPECT_LT(std::abs(value(dahl, "FC2") - 0.1268), 0.5 * std::abs(value(plain, "FC2") - 0.1268));
    // The validation gap shrinks by more than half.
    EXPECT_LT(dahl["validation"]["relative_error"].get<double>(), 0.5 * plain["validation"]["relative_error"].get<double>());
}

TEST(PreslidingFriction, KeysNeedPreslidingDahlAndKnownValues) {
    const auto bad = jacobid_cli("identify --quiet --robot " + robot_file("bad.yaml", ", presliding_displacement: 1e-4") + " --in " +
                                 simulated("presliding_train.csv", "--seed 3 --noise-seed 4", "60"));
    EXPECT_NE(bad.exit_code, 0);
    EXPECT_NE(bad.err.find("presliding_displacement"), std::string::npos) << bad.err;
    const auto unknown = jacobid_cli("identify --quiet --robot " + robot_file("unknown.yaml", ", presliding: maxwell") + " --in " +
                                     simulated("presliding_train.csv", "--seed 3 --noise-seed 4", "60"));
    EXPECT_NE(unknown.exit_code, 0);
    EXPECT_NE(unknown.err.find("presliding"), std::string::npos) << unknown.err;
}

TEST(PreslidingFriction, DescriptionRoundTripsThroughYaml) {
    namespace jr = jacobid::robot;
    const jr::RobotDescription d = jr::parse_robot_description(
        "model: planar2r\nfriction: {presliding: dahl, presliding_displacement: [2e-4, 8e-4], presliding_play: 1e-4}\nparameters: {FD2: 0.5}\n",
        "in.yaml");
    const jr::RobotDescription again = jr::parse_robot_description(jr::to_yaml(d), "again.yaml");
    EXPECT_TRUE(again.presliding);
    EXPECT_FALSE(again.presliding_displacement_auto);
    EXPECT_EQ(again.presliding_displacements, (std::vector<double>{2e-4, 8e-4}));
    EXPECT_EQ(again.presliding_play, 1e-4);
    const auto model = jr::make_robot_model(again);
    EXPECT_EQ(model->parameter_names().back(), "FD2");
    EXPECT_EQ(jr::true_parameters(again, *model)[model->parameter_index("FD2")], 0.5);
    const jr::RobotDescription automatic = jr::parse_robot_description("model: planar2r\nfriction: {presliding: dahl}\n", "auto.yaml");
    EXPECT_TRUE(jr::parse_robot_description(jr::to_yaml(automatic), "again.yaml").presliding_displacement_auto);
}

}  // namespace
