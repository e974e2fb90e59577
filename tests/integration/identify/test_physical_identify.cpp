// SPDX-License-Identifier: MIT
// identify --physical on a 6-axis arm (issue 16's acceptance, against the simulator's ground truth): a
// short, poorly exciting log of the UR5-like arm, identified with a "CAD" description whose inertial values
// are 30 % off (the prior), gives OLS/WLS parameters that break physical signs; --physical gives none, its
// held-out torque error (an independent log) is at most 1.05x the unconstrained one, and its standard
// parameters are closer to the truth than the unconstrained solution moved to the nearest physical point.
// Then the shared real UR10e logs (skipped with a message when absent): no violation, validation error at
// most 1.05x WLS's.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "identify/physical/physical_least_squares.hpp"
#include "realdata.hpp"
#include "robot/robot_description.hpp"
#include "robot/serial_robot_model.hpp"
#include "run_command.hpp"
#include "scratch_directory.hpp"

namespace {

namespace fs = std::filesystem;
using jacobid::test::run_command;

const std::string kJacobid = JACOBID_EXECUTABLE;
const std::string kRobot = std::string(JACOBID_SOURCE_DIR) + "/examples/robots/ur5_like.yaml";

nlohmann::json identify_json(const std::string& args) {
    const auto r = run_command(kJacobid + " identify --quiet --format json " + args);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return r.exit_code == 0 ? nlohmann::json::parse(r.out)["methods"]["jacobi"] : nlohmann::json{};
}

// sum ((s - truth) / unit)^2 over the standard parameters.
double distance(const nlohmann::json& standard, const jacobid::robot::SerialRobotModel& model, const Eigen::VectorXd& truth) {
    double d = 0.0;
    for (int i = 0; i < model.standard_parameter_count(); ++i) {
        const std::string& name = model.standard_names()[static_cast<std::size_t>(i)];
        const double e = (standard[name].get<double>() - truth[i]) / jacobid::identify::prior_unit(name);
        d += e * e;
    }
    return d;
}

TEST(PhysicalIdentify, ShortLogOfA6AxisArmBeatsTheProjectedLeastSquares) {
    const fs::path dir = jacobid::test::scratch_directory() / "physical_identify";
    fs::create_directories(dir);
    const std::string train = (dir / "short.csv").string(), held_out = (dir / "held_out.csv").string();
    ASSERT_EQ(run_command(kJacobid + " simulate --quiet --robot " + kRobot + " --duration 3 --seed 3 --noise-seed 4 --torque-noise 1 -o " + train).exit_code, 0);
    ASSERT_EQ(run_command(kJacobid + " simulate --quiet --robot " + kRobot + " --duration 5 --seed 5 --noise-seed 6 --torque-noise 1 -o " + held_out).exit_code, 0);

    // The CAD description: every given inertial value 30 % off, alternately up and down.
    jacobid::robot::RobotDescription cad = jacobid::robot::load_robot_description(kRobot);
    for (std::size_t i = 0; i < cad.parameters.size(); ++i) cad.parameters[i].second *= i % 2 ? 0.7 : 1.3;
    const std::string cad_file = (dir / "cad.yaml").string();
    std::ofstream(cad_file) << jacobid::robot::to_yaml(cad);

    const std::string common = "--robot " + cad_file + " --in " + train + " --validate " + held_out;
    const nlohmann::json ols = identify_json(common);
    const nlohmann::json physical = identify_json(common + " --physical");
    ASSERT_FALSE(ols.is_null());
    ASSERT_FALSE(physical.is_null());
    EXPECT_GE(ols["plausibility_violations"].size(), 1u) << "the short log no longer breaks a physical sign: the test proves nothing";
    EXPECT_EQ(physical["plausibility_violations"].size(), 0u) << physical["plausibility_violations"].dump();
    EXPECT_TRUE(physical["physical"]["converged"].get<bool>());
    EXPECT_LE(physical["validation"]["relative_error"].get<double>(), 1.05 * ols["validation"]["relative_error"].get<double>());

    const jacobid::robot::RobotDescription truth_description = jacobid::robot::load_robot_description(kRobot);
    const auto model = jacobid::robot::make_robot_model(truth_description);
    const auto& serial = dynamic_cast<const jacobid::robot::SerialRobotModel&>(*model);
    const Eigen::VectorXd truth = jacobid::robot::standard_values(truth_description, serial);
    const double d_physical = distance(physical["physical"]["standard"], serial, truth);
    const double d_projected = distance(physical["physical"]["projected_standard"], serial, truth);
    EXPECT_LT(d_physical, d_projected) << "physical " << d_physical << ", projected least squares " << d_projected;
}

// Presliding columns (friction presliding: dahl) are their own standard parameters: --physical keeps them,
// with FDj >= 0 like the other friction coefficients, beside the consistent rigid body.
TEST(PhysicalIdentify, DahlPreslidingCoefficientsAreKeptNonNegative) {
    const fs::path dir = jacobid::test::scratch_directory() / "physical_dahl";
    fs::create_directories(dir);
    jacobid::robot::RobotDescription truth = jacobid::robot::load_robot_description(kRobot);
    const std::string plain = jacobid::robot::to_yaml(truth);
    const std::string friction = "friction:\n  coulomb: smooth\n  alpha: 100\n";
    ASSERT_NE(plain.find(friction), std::string::npos) << "ur5_like.yaml's friction block changed: " << plain;
    std::string dahl = plain;
    dahl.replace(dahl.find(friction), friction.size(), friction + "  presliding: dahl\n  presliding_displacement: 5e-4\n");
    const std::string truth_file = (dir / "truth.yaml").string();
    std::ofstream(truth_file) << dahl << "  FD1: 1.0\n  FD2: 2.0\n  FD3: 1.0\n  FD4: 0.3\n  FD5: 0.3\n  FD6: 0.2\n";
    const std::string log = (dir / "dahl.csv").string();
    const auto sim = run_command(kJacobid + " simulate --quiet --robot " + truth_file + " --duration 6 --seed 3 --noise-seed 4 --torque-noise 0.5 -o " + log);
    ASSERT_EQ(sim.exit_code, 0) << sim.err;
    const nlohmann::json physical = identify_json("--robot " + truth_file + " --in " + log + " --physical");
    ASSERT_FALSE(physical.is_null());
    EXPECT_TRUE(physical["physical"]["converged"].get<bool>());
    EXPECT_EQ(physical["plausibility_violations"].size(), 0u) << physical["plausibility_violations"].dump();
    const double truth_fd[6] = {1.0, 2.0, 1.0, 0.3, 0.3, 0.2};
    for (int j = 1; j <= 6; ++j) {
        const std::string name = "FD" + std::to_string(j);
        ASSERT_TRUE(physical["physical"]["standard"].contains(name)) << name;
        const double fd = physical["physical"]["standard"][name].get<double>();
        EXPECT_GE(fd, 0.0) << name;
        EXPECT_NEAR(fd, truth_fd[j - 1], 0.3 * truth_fd[j - 1] + 0.05) << name;
    }
}

TEST(PhysicalIdentify, OptionsAreCheckedAndAPlanarModelIsRefused) {
    const auto both = run_command(kJacobid + " identify --quiet --robot " + kRobot + " --in x.csv --physical --semi-physical");
    EXPECT_NE(both.exit_code, 0);
    EXPECT_NE(both.err.find("--physical and --semi-physical"), std::string::npos) << both.err;
    const fs::path dir = jacobid::test::scratch_directory() / "physical_planar";
    fs::create_directories(dir);
    const std::string log = (dir / "p.csv").string();
    ASSERT_EQ(run_command(kJacobid + " simulate --quiet --duration 3 -o " + log).exit_code, 0);
    const auto planar = run_command(kJacobid + " identify --quiet --in " + log + " --robot " + std::string(JACOBID_SOURCE_DIR) +
                                    "/examples/robots/planar2r.yaml --physical");
    EXPECT_NE(planar.exit_code, 0);
    EXPECT_NE(planar.err.find("model mdh or urdf"), std::string::npos) << planar.err;
    const std::string arm_log = (dir / "arm.csv").string();
    ASSERT_EQ(run_command(kJacobid + " simulate --quiet --robot " + kRobot + " --duration 1 -o " + arm_log).exit_code, 0);
    const auto iv = run_command(kJacobid + " identify --quiet --in " + arm_log + " --robot " + kRobot + " --physical --estimator iv");
    EXPECT_NE(iv.exit_code, 0);
    EXPECT_NE(iv.err.find("--physical with --estimator iv"), std::string::npos) << iv.err;
    const auto weight = run_command(kJacobid + " identify --quiet --in " + log + " --robot " + kRobot + " --physical --prior-weight -1");
    EXPECT_NE(weight.exit_code, 0);
    EXPECT_NE(weight.err.find("--prior-weight"), std::string::npos) << weight.err;
}

TEST(PhysicalIdentify, RealUr10eHasNoViolationAndValidatesAsWellAsWls) {
    REQUIRE_REALDATA();
    const fs::path data = jacobid::test::realdata_dir() / "ur10e";
    const fs::path dir = jacobid::test::scratch_directory() / "physical_ur10e";
    fs::create_directories(dir);
    const std::string robot = (dir / "ur10e.yaml").string();
    std::ofstream(robot) << "model: urdf\nurdf: " << (data / "ur10e.urdf").string()
                         << "\ngravity: [0, 0, -9.81]\nfriction: {coulomb: smooth, offset: true}\nrotor_inertia: true\n";
    const std::string common = "--robot " + robot + " --log-format " + (jacobid::test::log_formats_dir() / "ur10e.yaml").string() + " --in " +
                               (data / "identification" / "ur-20_02_19_14harm50sec.csv").string() + " --validate " +
                               (data / "validation" / "ur-20_01_22-joint_5.csv").string();
    const nlohmann::json wls = identify_json(common);
    const nlohmann::json physical = identify_json(common + " --physical");
    ASSERT_FALSE(physical.is_null());
    EXPECT_GE(wls["plausibility_violations"].size(), 1u);
    EXPECT_EQ(physical["plausibility_violations"].size(), 0u) << physical["plausibility_violations"].dump();
    EXPECT_LE(physical["validation"]["relative_error"].get<double>(), 1.05 * wls["validation"]["relative_error"].get<double>());
}

}  // namespace
