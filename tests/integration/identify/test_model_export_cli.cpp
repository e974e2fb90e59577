// SPDX-License-Identifier: MIT
// identify --export-urdf / --export-robot end to end (issue 16's acceptance): a simulated log of the test arm
// (tests/data/export_arm.urdf) and the real UR10e run (skipped when the shared logs are absent) identified
// with the exports asked for; then
//   - the exported URDF read by urdfdom into KDL (urdf_kdl_reference.hpp, not jacobid's urdf_chain): KDL's
//     torques plus IA qdd + FV qd + FC c(qd) + FOFF (IA, FOFF from the exported description, alpha checked
//     against the JSON's coulomb_smoothing) equal the identified model's, regressor x identified base values,
//     to 1e-9 relative on random states;
//   - the exported description loaded by jacobid gives the identified base values;
//   - the simulated UR5-like (mdh) arm: --export-robot alone round-trips, and --physical is implied;
//   - bad input: planar2r, mdh with --export-urdf, a missing directory, a path that cannot be written.
#include <gtest/gtest.h>

#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>

#include "realdata.hpp"
#include "robot/robot_description.hpp"
#include "robot/serial_robot_model.hpp"
#include "run_command.hpp"
#include "scratch_directory.hpp"
#include "urdf_kdl_reference.hpp"

namespace {

namespace fs = std::filesystem;
using namespace jacobid;
using test::run_command;

const std::string kJacobid = JACOBID_EXECUTABLE;
const std::string kSource = JACOBID_SOURCE_DIR;

std::string read_file(const fs::path& path) { return test::read_text_file(path.string()); }

nlohmann::json identify_json(const std::string& args) {
    const auto r = run_command(kJacobid + " identify --quiet --format json " + args);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return r.exit_code == 0 ? nlohmann::json::parse(r.out) : nlohmann::json{};
}

// The identified base values of one method, in the model's order.
Eigen::VectorXd identified_base(const nlohmann::json& method) {
    const auto& order = method["parameter_order"];
    Eigen::VectorXd x(static_cast<Eigen::Index>(order.size()));
    for (std::size_t i = 0; i < order.size(); ++i) x[static_cast<Eigen::Index>(i)] = method["parameters"][order[i].get<std::string>()]["value"].get<double>();
    return x;
}

// The exported description loaded by jacobid gives the identified base values.
void expect_description_round_trips(const fs::path& yaml, const Eigen::VectorXd& x) {
    const robot::RobotDescription loaded = robot::load_robot_description(yaml.string());
    const auto model = robot::make_robot_model(loaded);
    const auto& serial = dynamic_cast<const robot::SerialRobotModel&>(*model);
    const Eigen::VectorXd reloaded = serial.base_values(robot::standard_values(loaded, serial));
    ASSERT_EQ(reloaded.size(), x.size());
    EXPECT_LT((reloaded - x).norm(), 1e-9 * x.norm()) << "reloaded\n" << reloaded.transpose() << "\nidentified\n" << x.transpose();
}

double parameter(const robot::RobotDescription& d, const std::string& name) {
    for (const auto& [n, v] : d.parameters) {
        if (n == name) return v;
    }
    return 0.0;
}

// The worst relative difference between KDL on the exported URDF (+ the joint terms) and the identified model
// (the exported description's regressor x the identified base values) over random states.
double kdl_disagreement(const fs::path& urdf, const fs::path& yaml, const nlohmann::json& method, const Eigen::VectorXd& limits) {
    const robot::RobotDescription loaded = robot::load_robot_description(yaml.string());
    const auto model = robot::make_robot_model(loaded);
    const auto& serial = dynamic_cast<const robot::SerialRobotModel&>(*model);
    const Eigen::VectorXd x = identified_base(method);
    const test::UrdfKdlReference kdl(read_file(urdf));
    const int n = serial.joint_count();
    test::JointTerms terms;
    for (int j = 0; j < n; ++j) {
        terms.ia.push_back(parameter(loaded, "IA" + std::to_string(j + 1)));
        terms.foff.push_back(parameter(loaded, "FOFF" + std::to_string(j + 1)));
        // The smoothing identify chose (its JSON), which the description must have fixed.
        const double alpha = method["coulomb_smoothing"]["joints"][static_cast<std::size_t>(j)]["alpha"].get<double>();
        EXPECT_DOUBLE_EQ(loaded.coulomb_alpha.at(static_cast<std::size_t>(j)), alpha);
        terms.coulomb.push_back({robot::CoulombModel::SmoothAtan, alpha});
    }
    return test::worst_relative_difference(kdl, serial, x, loaded.gravity, terms, limits);
}

// The test arm (tests/data/export_arm.urdf) described with `extra` (friction, parameters) in DIR/arm.yaml, and
// an 8 s simulated log of it in DIR/log.csv.
struct SimulatedArm {
    std::string robot, log;
};
SimulatedArm simulated_arm(const fs::path& dir, const std::string& extra) {
    fs::create_directories(dir);
    SimulatedArm arm{(dir / "arm.yaml").string(), (dir / "log.csv").string()};
    std::ofstream(arm.robot) << "model: urdf\nurdf: " << kSource << "/tests/data/export_arm.urdf\n" << extra;
    EXPECT_EQ(run_command(kJacobid + " simulate --quiet --robot " + arm.robot + " --duration 8 --seed 3 --noise-seed 4 --torque-noise 0.2 -o " + arm.log).exit_code, 0);
    return arm;
}

TEST(ModelExportCli, SimulatedUrdfArmExportsAUrdfThatKdlAgreesWith) {
    const fs::path dir = test::scratch_directory() / "export_arm";
    const auto [robot, log] = simulated_arm(dir, "friction: {coulomb: smooth, alpha: auto, offset: true}\nrotor_inertia: true\n"
                                                 "parameters: {IA1: 0.05, IA2: 0.04, IA3: 0.02, IA4: 0.5, FV1: 0.3, FC1: 0.8, FV3: 0.2, FC3: 0.5, FOFF2: 0.3}\n");
    const fs::path urdf = dir / "out" / "arm.urdf", yaml = dir / "out" / "arm.yaml";
    fs::create_directories(dir / "out");
    const nlohmann::json j = identify_json("--robot " + robot + " --in " + log + " --method both --export-urdf " + urdf.string() + " --export-robot " + yaml.string());
    ASSERT_FALSE(j.is_null());
    EXPECT_EQ(j["export"]["method"], "jacobi");
    EXPECT_EQ(j["export"]["constraint"], "physical");  // implied
    EXPECT_EQ(j["export"]["urdf"], urdf.string());
    const nlohmann::json& jacobi = j["methods"]["jacobi"];
    ASSERT_TRUE(jacobi.contains("physical"));
    EXPECT_NE(read_file(yaml).find("urdf: arm.urdf"), std::string::npos) << "the description names the exported URDF beside it";
    expect_description_round_trips(yaml, identified_base(jacobi));
    const double worst = kdl_disagreement(urdf, yaml, jacobi, Eigen::Vector4d(2.5, 2.0, 3.0, 0.1));
    EXPECT_LT(worst, 1e-9);
    // The URDF alone, from a --semi-physical fit (kept, not replaced by the implied --physical).
    const fs::path semi = dir / "out" / "semi.urdf";
    const nlohmann::json s = identify_json("--robot " + robot + " --in " + log + " --semi-physical --export-urdf " + semi.string());
    ASSERT_FALSE(s.is_null());
    EXPECT_EQ(s["export"]["constraint"], "semi-physical");
    EXPECT_TRUE(s["export"]["warnings"].is_array());
    EXPECT_FALSE(s["export"].contains("robot"));
    EXPECT_TRUE(fs::exists(semi));
    // The description alone of a urdf model: the original URDF, every standard value in `parameters`.
    const fs::path alone = dir / "out" / "alone.yaml";
    const nlohmann::json a = identify_json("--robot " + robot + " --in " + log + " --export-robot " + alone.string());
    ASSERT_FALSE(a.is_null());
    EXPECT_NE(read_file(alone).find("export_arm.urdf"), std::string::npos);
    expect_description_round_trips(alone, identified_base(a["methods"]["jacobi"]));
    // The description's own files hold the prior: never overwritten.
    const auto own = run_command(kJacobid + " identify --quiet --robot " + robot + " --in " + log + " --export-urdf " + kSource +
                                 "/tests/data/export_arm.urdf");
    EXPECT_EQ(own.exit_code, 2);
    EXPECT_NE(own.err.find("is the input given to the urdf: of --robot"), std::string::npos) << own.err;
    const auto own_yaml = run_command(kJacobid + " identify --quiet --robot " + robot + " --in " + log + " --export-robot " + robot);
    EXPECT_EQ(own_yaml.exit_code, 2);
    EXPECT_NE(own_yaml.err.find("is the input given to --robot"), std::string::npos) << own_yaml.err;
    // The same paths twice are refused.
    const auto twice = run_command(kJacobid + " identify --quiet --robot " + robot + " --in " + log + " --export-urdf " + semi.string() +
                                   " --export-robot " + semi.string());
    EXPECT_EQ(twice.exit_code, 2);
    EXPECT_NE(twice.err.find("--export-robot " + semi.string() + ": is also the output of --export-urdf"), std::string::npos) << twice.err;
}

TEST(ModelExportCli, PreslidingLevelsAndDisplacementsGoToTheDescription) {
    const fs::path dir = test::scratch_directory() / "export_dahl";
    const auto [robot, log] = simulated_arm(dir, "friction: {coulomb: smooth, alpha: 100, presliding: dahl}\n"
                                                 "parameters: {FV1: 0.3, FC1: 0.8, FV3: 0.2, FC3: 0.5, FD1: 0.3, FD2: 0.2, FD3: 0.1, FD4: 0.5}\n");
    const fs::path urdf = dir / "arm_identified.urdf", yaml = dir / "arm_identified.yaml";
    const nlohmann::json j = identify_json("--robot " + robot + " --in " + log + " --export-urdf " + urdf.string() + " --export-robot " + yaml.string());
    ASSERT_FALSE(j.is_null());
    EXPECT_TRUE(j["export"]["not_in_urdf"].contains("FD1")) << j["export"].dump();
    EXPECT_NE(read_file(urdf).find("FD4 = "), std::string::npos) << "the joint comment names the presliding level";
    const robot::RobotDescription loaded = robot::load_robot_description(yaml.string());
    EXPECT_TRUE(loaded.presliding);
    EXPECT_FALSE(loaded.presliding_displacement_auto);
    const nlohmann::json& jacobi = j["methods"]["jacobi"];
    ASSERT_EQ(loaded.presliding_displacements.size(), 4u);
    for (std::size_t k = 0; k < 4; ++k) {
        EXPECT_DOUBLE_EQ(loaded.presliding_displacements[k], jacobi["presliding_displacement"]["joints"][k]["displacement"].get<double>());
    }
    // The levels and the rigid body: the loaded description's values are the identified ones.
    const auto model = robot::make_robot_model(loaded);
    const Eigen::VectorXd reloaded = robot::true_parameters(loaded, *model), x = identified_base(jacobi);
    ASSERT_EQ(reloaded.size(), x.size());
    EXPECT_LT((reloaded - x).norm(), 1e-9 * x.norm()) << "reloaded\n" << reloaded.transpose() << "\nidentified\n" << x.transpose();
}

TEST(ModelExportCli, MdhArmExportsItsDescriptionAndImpliesPhysical) {
    const fs::path dir = test::scratch_directory() / "export_mdh";
    fs::create_directories(dir);
    const std::string robot = kSource + "/examples/robots/ur5_like.yaml", log = (dir / "log.csv").string();
    ASSERT_EQ(run_command(kJacobid + " simulate --quiet --robot " + robot + " --duration 3 --seed 3 --noise-seed 4 --torque-noise 1 -o " + log).exit_code, 0);
    const fs::path yaml = dir / "ur5.yaml";
    const nlohmann::json j = identify_json("--robot " + robot + " --in " + log + " --export-robot " + yaml.string());
    ASSERT_FALSE(j.is_null());
    EXPECT_TRUE(j["methods"]["jacobi"].contains("physical"));
    EXPECT_EQ(j["export"]["robot"], yaml.string());
    expect_description_round_trips(yaml, identified_base(j["methods"]["jacobi"]));
    // --semi-physical is kept when given.
    const nlohmann::json semi = identify_json("--robot " + robot + " --in " + log + " --semi-physical --export-robot " + yaml.string());
    ASSERT_FALSE(semi.is_null());
    EXPECT_EQ(semi["export"]["constraint"], "semi-physical");
    expect_description_round_trips(yaml, identified_base(semi["methods"]["jacobi"]));
    // The text report says what was written.
    const auto text = run_command(kJacobid + " identify --quiet --robot " + robot + " --in " + log + " --export-robot " + yaml.string());
    EXPECT_NE(text.out.find("exported the jacobi method's --physical standard parameters: " + yaml.string()), std::string::npos) << text.out;
}

TEST(ModelExportCli, BadInputIsRefusedWithTheOptionNamed) {
    const fs::path dir = test::scratch_directory() / "export_bad";
    fs::create_directories(dir);
    const std::string log = (dir / "log.csv").string(), mdh = kSource + "/examples/robots/ur5_like.yaml";
    ASSERT_EQ(run_command(kJacobid + " simulate --quiet --robot " + mdh + " --duration 1 -o " + log).exit_code, 0);
    const auto refused = [&](const std::string& args, const std::string& message) {
        const auto r = run_command(kJacobid + " identify --quiet --in " + log + " " + args);
        EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.err;
        EXPECT_NE(r.err.find(message), std::string::npos) << args << "\n" << r.err;
    };
    refused("--robot " + kSource + "/examples/robots/planar2r.yaml --export-robot " + (dir / "p.yaml").string(),
            "--export-robot: model planar2r has no standard (per-link) parameters");
    refused("--robot " + mdh + " --export-urdf " + (dir / "a.urdf").string(), "--export-urdf " + (dir / "a.urdf").string() + ": model mdh has no URDF");
    refused("--robot " + mdh + " --export-robot " + (dir / "missing" / "a.yaml").string(), "does not exist");
    refused("--robot " + mdh + " --export-robot -", "--export-robot: expected a file path, got '-'");
    // A directory is not a writable file: found by the output guard before the work, named by the option.
    refused("--robot " + mdh + " --export-robot " + dir.string(), "--export-robot " + dir.string() + ": is a directory, expected a file name");
}

TEST(ModelExportCli, RealUr10eExportAgreesWithKdl) {
    REQUIRE_REALDATA();
    const fs::path data = test::realdata_dir() / "ur10e";
    const fs::path dir = test::scratch_directory() / "export_ur10e";
    fs::create_directories(dir);
    const std::string robot = (dir / "ur10e.yaml").string();
    std::ofstream(robot) << "model: urdf\nurdf: " << (data / "ur10e.urdf").string()
                         << "\ngravity: [0, 0, -9.81]\nfriction: {coulomb: smooth, offset: true}\nrotor_inertia: true\n";
    const fs::path urdf = dir / "ur10e_identified.urdf", yaml = dir / "ur10e_identified.yaml";
    const nlohmann::json j = identify_json("--robot " + robot + " --log-format " + (test::log_formats_dir() / "ur10e.yaml").string() + " --in " +
                                           (data / "identification" / "ur-20_02_19_14harm50sec.csv").string() + " --export-urdf " + urdf.string() +
                                           " --export-robot " + yaml.string());
    ASSERT_FALSE(j.is_null());
    const nlohmann::json& jacobi = j["methods"]["jacobi"];
    expect_description_round_trips(yaml, identified_base(jacobi));
    const double worst = kdl_disagreement(urdf, yaml, jacobi, Eigen::VectorXd::Constant(6, 3.0));
    EXPECT_LT(worst, 1e-9);
    std::cout << "UR10e export: KDL vs identified model, worst relative torque difference " << worst << ", --physical solve "
              << jacobi["physical"]["seconds"].get<double>() << " s\n";
    // The URDF keeps its transmissions and the rest: only inertials and dynamics change.
    EXPECT_NE(read_file(urdf).find("<transmission"), std::string::npos);
}

}  // namespace
