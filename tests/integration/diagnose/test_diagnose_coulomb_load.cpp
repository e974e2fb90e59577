// SPDX-License-Identifier: MIT
// The coulomb_load effect (issue 15: Coulomb friction growing with the joint's gravity load) on a 2R arm in a
// vertical plane: the simulator's injected torque against the gravity torque written out by hand, the
// injected effect against the description's friction: coulomb_load (two code paths, one robot), and the
// diagnosis naming it on simulated data and naming nothing on clean data. Ground truth is the simulation's.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "diagnose_test_support.hpp"
#include "io/csv_table.hpp"
#include "robot/robot_description.hpp"

namespace jacobid::test {
namespace {

constexpr double kM2 = 2.0, kMX2 = 0.124, kMY2 = 0.0019, kD2 = 0.5, kG = 9.81;

// The paper's Table II on a vertical plane (gravity along -y of the base); `friction` appended to its friction map.
std::string vertical_robot(const std::string& name, const std::string& friction = "", const std::string& levels = "") {
    const std::string path = scratch(name);
    std::ofstream(path) << "model: mdh\ngravity: [0, -9.81, 0]\njoints:\n"
                           "  - {name: j1, sigma: 0, alpha: 0, d: 0, theta: 0, r: 0, position: q1, torque: tau1}\n"
                           "  - {name: j2, sigma: 0, alpha: 0, d: 0.5, theta: 0, r: 0, position: q2, torque: tau2}\n"
                           "friction: {coulomb: smooth, alpha: 100"
                        << friction << "}\nparameters: {ZZ1: 2.996, M2: 2.0, FV1: 0.248, FC1: 0.431, ZZ2: 0.059, MX2: 0.124, MY2: 0.0019, "
                        << "FV2: 0.0144, FC2: 0.1268" << levels << "}\n";
    return path;
}

CommandResult simulate(const std::string& robot, const std::string& out, double duration, int seed, const std::string& extra) {
    return run_command(std::string(JACOBID_EXECUTABLE) + " simulate --quiet --robot " + robot + " --out " + out + " --duration " +
                       std::to_string(duration) + " --torque-noise 0.02,0.005 --seed " + std::to_string(seed) + " --noise-seed " +
                       std::to_string(seed + 1000) + " " + extra);
}

double smooth_sign(double v) { return 2.0 / M_PI * std::atan(100.0 * v); }

TEST(CoulombLoadEffect, InjectedTorqueIsTheHandGravityLoadTimesTheSign) {
    const std::string robot = vertical_robot("vertical.yaml"), states = scratch("coulomb_load.states.csv");
    const auto r = simulate(robot, scratch("coulomb_load_states.csv"), 3, 5,
                            "--states " + states + " --effect coulomb_load:joint=1,value=0.03 --effect coulomb_load:joint=2,value=0.08");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const io::CsvTable t = io::read_csv(states);
    const auto description = robot::load_robot_description(robot);
    const auto model = robot::make_robot_model(description);
    const Eigen::VectorXd x = robot::true_parameters(description, *model);
    Eigen::MatrixXd D(2, model->parameter_count());
    const std::size_t n = t.column("t").size();
    ASSERT_GT(n, 1000u);
    for (std::size_t k = 0; k < n; k += 7) {
        const double q[2] = {t.column("q1")[k], t.column("q2")[k]}, qd[2] = {t.column("qd1")[k], t.column("qd2")[k]},
                     qdd[2] = {t.column("qdd1")[k], t.column("qdd2")[k]};
        model->regressor(q, qd, qdd, D);
        const Eigen::VectorXd nominal = D * x;
        // dU/dq of U = g (M2 d2 sin q1 + MX2 sin q12 + MY2 cos q12).
        const double g2 = kG * (kMX2 * std::cos(q[0] + q[1]) - kMY2 * std::sin(q[0] + q[1]));
        const double g1 = kG * kM2 * kD2 * std::cos(q[0]) + g2;
        ASSERT_NEAR(t.column("tau1")[k] - nominal[0], 0.03 * std::abs(g1) * smooth_sign(qd[0]), 1e-9) << "sample " << k;
        ASSERT_NEAR(t.column("tau2")[k] - nominal[1], 0.08 * std::abs(g2) * smooth_sign(qd[1]), 1e-9) << "sample " << k;
    }
}

TEST(CoulombLoadEffect, TheEffectAndTheFrictionOptionSimulateTheSameRobot) {
    // Injected as an effect (the inertia-matrix route through the augmented model) and as the description's
    // own friction (the articulated-body route through LoadFrictionModel): the same noise-free motion.
    const std::string as_effect = scratch("load_effect.states.csv"), as_option = scratch("load_option.states.csv");
    ASSERT_EQ(simulate(vertical_robot("vertical.yaml"), scratch("load_effect.csv"), 5, 9,
                       "--states " + as_effect + " --effect coulomb_load:joint=1,value=0.03 --effect coulomb_load:joint=2,value=0.08")
                  .exit_code,
              0);
    ASSERT_EQ(simulate(vertical_robot("vertical_load.yaml", ", coulomb_load: abs", ", FCL1: 0.03, FCL2: 0.08"), scratch("load_option.csv"), 5, 9,
                       "--states " + as_option)
                  .exit_code,
              0);
    const io::CsvTable a = io::read_csv(as_effect), b = io::read_csv(as_option);
    for (const char* column : {"q1", "q2", "tau1", "tau2"}) {
        ASSERT_EQ(a.column(column).size(), b.column(column).size());
        for (std::size_t k = 0; k < a.column(column).size(); ++k) ASSERT_NEAR(a.column(column)[k], b.column(column)[k], 1e-8) << column << " " << k;
    }
}

TEST(CoulombLoadEffect, DiagnoseNamesItAndNothingOnCleanData) {
    const std::string robot = vertical_robot("vertical.yaml");
    const std::string log = scratch("load_diag.csv"), val = scratch("load_diag.val.csv");
    const std::string effect = "--effect coulomb_load:joint=2,value=0.08";
    ASSERT_EQ(simulate(robot, log, 30, 21, effect).exit_code, 0);
    ASSERT_EQ(simulate(robot, val, 20, 22, effect).exit_code, 0);
    const auto r = run_command(std::string(JACOBID_EXECUTABLE) + " diagnose --quiet --robot " + robot + " --in " + log + " --validate " + val +
                               " --format json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto d = nlohmann::json::parse(r.out);
    ASSERT_GE(d["effects"].size(), 1u) << r.out;
    EXPECT_EQ(d["effects"][0]["name"], "coulomb_load");
    EXPECT_EQ(d["effects"][0]["joint"], 2);
    EXPECT_NEAR(d["effects"][0]["value"].get<double>(), 0.08, 0.2 * 0.08);
    const double before = d["before"]["heldout_rms"][1].get<double>(), after = d["after"]["heldout_rms"][1].get<double>();
    EXPECT_LE(after, 0.5 * before) << "held-out RMS " << before << " -> " << after;

    const std::string clean = scratch("load_clean.csv");
    ASSERT_EQ(simulate(robot, clean, 30, 21, "").exit_code, 0);
    const auto c = run_command(std::string(JACOBID_EXECUTABLE) + " diagnose --quiet --robot " + robot + " --in " + clean + " --format json");
    ASSERT_EQ(c.exit_code, 0) << c.err;
    EXPECT_TRUE(nlohmann::json::parse(c.out)["effects"].empty()) << c.out;
}

TEST(CoulombLoadEffect, ARobotGravityNeverLoadsIsRefusedByName) {
    const auto r = simulate_log(scratch("load_flat.csv"), 2, 3, "--effect coulomb_load:joint=2,value=0.08");
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("coulomb_load j2"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace jacobid::test
