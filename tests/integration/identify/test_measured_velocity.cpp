// SPDX-License-Identifier: MIT
// identify --velocity measured: the regressor's velocities come from the log's own velocity columns. The
// "measured" velocity is the simulator's noise-free velocity (its --states file) plus noise, so the expected
// parameters are the simulation's truth (the paper's Table II); a velocity column scaled by 2 must move the
// viscous coefficients by about that factor, which proves the column is really used.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "run_command.hpp"
#include "simulated_log.hpp"
#include "scratch_directory.hpp"

namespace {

using nlohmann::json;

std::string path(const std::string& name) { return (jacobid::test::scratch_directory() / name).string(); }
jacobid::test::CommandResult jacobid_cli(const std::string& args) { return jacobid::test::run_command(std::string(JACOBID_EXECUTABLE) + " " + args); }

std::vector<std::vector<std::string>> read_rows(const std::string& file) {
    std::ifstream in(file);
    std::vector<std::vector<std::string>> rows;
    for (std::string line; std::getline(in, line);) {
        std::vector<std::string> cells;
        std::stringstream ss(line);
        for (std::string c; std::getline(ss, c, ',');) cells.push_back(c);
        rows.push_back(cells);
    }
    return rows;
}

// The measured log (t,q1,q2,tau1,tau2) with qd1,qd2 = scale x true velocity + N(0, 0.002) rad/s.
std::string log_with_velocity(const std::string& name, double scale) {
    const std::string log = path("mv.csv"), states = path("mv.states.csv");
    std::ifstream probe(log);
    if (!probe) {
        std::ofstream(path("robot.yaml")) << "model: planar2r\nL1: 0.5\nfriction: {coulomb: smooth, alpha: 100}\n";
        const auto r = jacobid::test::simulated_log(log, "--quiet --robot " + path("robot.yaml") + " --states " + states +
                                                    " --duration 60 --encoder-counts 65536 --torque-noise 0.05,0.01 --seed 1");
        EXPECT_EQ(r.exit_code, 0) << r.err;
    }
    const auto measured = read_rows(log), truth = read_rows(states);
    // The measured columns (then the reference, which this test does not use).
    EXPECT_EQ(measured.front(), (std::vector<std::string>{"t", "q1", "q2", "tau1", "tau2", "q_ref1", "q_ref2", "qd_ref1", "qd_ref2"}));
    EXPECT_EQ(truth.front()[3], "qd1");
    EXPECT_EQ(measured.size(), truth.size());
    std::mt19937 rng(5);
    std::normal_distribution<double> noise(0.0, 0.002);
    const std::string out = path(name);
    std::ofstream o(out);
    o << "t,q1,q2,tau1,tau2,qd1,qd2\n";
    for (std::size_t k = 1; k < measured.size(); ++k) {
        const auto& m = measured[k];
        o << m[0] << ',' << m[1] << ',' << m[2] << ',' << m[3] << ',' << m[4];
        for (int j = 0; j < 2; ++j) o << ',' << scale * std::stod(truth[k][3 + static_cast<std::size_t>(j)]) + noise(rng);
        o << '\n';
    }
    return out;
}

json identify(const std::string& log, const std::string& args) {
    const auto r = jacobid_cli("identify --quiet --robot " + path("robot.yaml") + " --in " + log + " --format json " + args);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return json::parse(r.out.empty() ? "{}" : r.out);
}

double value(const json& j, const std::string& method, const std::string& name) { return j["methods"][method]["parameters"][name]["value"].get<double>(); }

}  // namespace

TEST(MeasuredVelocity, LoggedVelocityIdentifiesTheTruthAndIsReallyUsed) {
    const std::string good = log_with_velocity("mv_good.csv", 1.0), doubled = log_with_velocity("mv_doubled.csv", 2.0);
    const json j = identify(good, "--velocity measured --method both --torque-delay 0");
    const std::pair<const char*, double> truth[] = {{"ZZ1R", 3.496}, {"FV1", 0.248}, {"FC1", 0.431}, {"ZZ2", 0.059}, {"MX2", 0.124}, {"FC2", 0.1268}};
    for (const char* method : {"jacobi", "butterworth"}) {
        for (const auto& [name, t] : truth) EXPECT_NEAR(value(j, method, name), t, 0.01 * t) << method << " " << name;
    }
    // Twice the velocity: the viscous terms halve (FV qd must still explain the same torque).
    const json d = identify(doubled, "--velocity measured --torque-delay 0");
    EXPECT_NEAR(value(d, "jacobi", "FV1"), 0.5 * 0.248, 0.05 * 0.248);
    // Differentiated (the default) ignores the column.
    const json differentiated = identify(doubled, "--torque-delay 0");
    EXPECT_NEAR(value(differentiated, "jacobi", "FV1"), 0.248, 0.01 * 0.248);
}

// Noise-free data (no torque noise, no quantization) with the exact velocity logged: the Jacobi method must
// pass the measured velocity through the low-pass its torque goes through (the velocity kernel's), or the
// friction sees the filter mismatch the torque smoothing removes. Truth: the paper's Table II.
TEST(MeasuredVelocity, ExactLoggedVelocityGivesUnbiasedFrictionInTheJacobiMethod) {
    const std::string log = path("mv_exact.csv"), states = path("mv_exact.states.csv"), robot = path("robot_exact.yaml");
    std::ofstream(robot) << "model: planar2r\nL1: 0.5\nfriction: {coulomb: smooth, alpha: 100}\n";
    const auto r = jacobid::test::simulated_log(log, "--quiet --robot " + robot + " --states " + states +
                                                " --duration 40 --encoder-counts 0 --torque-noise 0 --seed 3");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto measured = read_rows(log), truth = read_rows(states);
    const std::string exact = path("mv_exact_qd.csv");
    std::ofstream o(exact);
    o << "t,q1,q2,tau1,tau2,qd1,qd2\n";
    for (std::size_t k = 1; k < measured.size(); ++k) {
        const auto& m = measured[k];
        o << m[0] << ',' << m[1] << ',' << m[2] << ',' << m[3] << ',' << m[4] << ',' << truth[k][3] << ',' << truth[k][4] << '\n';
    }
    o.close();
    const auto j = jacobid_cli("identify --quiet --robot " + robot + " --in " + exact + " --format json --velocity measured --torque-delay 0");
    ASSERT_EQ(j.exit_code, 0) << j.err;
    const json out = json::parse(j.out);
    for (const auto& [name, t] : {std::pair{"FV1", 0.248}, std::pair{"FC1", 0.431}, std::pair{"FV2", 0.0144}, std::pair{"FC2", 0.1268}}) {
        EXPECT_NEAR(value(out, "jacobi", name), t, 0.001 * t) << name;
    }
}

TEST(MeasuredVelocity, MissingColumnOrMismatchedMethodIsAnError) {
    log_with_velocity("mv_good.csv", 1.0);
    const auto missing = jacobid_cli("identify --robot " + path("robot.yaml") + " --in " + path("mv.csv") + " --velocity measured");
    EXPECT_EQ(missing.exit_code, 2);
    EXPECT_NE(missing.err.find("--velocity measured: "), std::string::npos) << missing.err;
    EXPECT_NE(missing.err.find("no measured velocity for joint 1"), std::string::npos) << missing.err;
    const auto mixed = jacobid_cli("identify --robot " + path("robot.yaml") + " --in " + path("mv.csv") + " --velocity butterworth");
    EXPECT_EQ(mixed.exit_code, 2);
    EXPECT_NE(mixed.err.find("--velocity butterworth with --method jacobi"), std::string::npos) << mixed.err;
}
