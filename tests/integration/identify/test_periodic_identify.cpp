// SPDX-License-Identifier: MIT
// identify --period on a simulated planar 2R that plays one trajectory period after period (simulate
// --trajectory): the period found from the positions alone is the table's length, the noise measured from
// the period-to-period spread is the simulator's torque noise, and the mean period identifies the truth.
// The references are what the test built: the trajectory's period, the simulator's noise and its truth file.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "run_command.hpp"
#include "scratch_directory.hpp"

namespace {

using nlohmann::json;
constexpr double kPi = 3.14159265358979323846;
constexpr double kPeriod = 4.0;  // s
constexpr int kPeriods = 5;
constexpr double kNoise[2] = {0.05, 0.01};  // N.m, the simulator's torque noise per joint

std::string path(const std::string& name) { return (jacobid::test::scratch_directory() / name).string(); }

jacobid::test::CommandResult jacobid_cli(const std::string& args) { return jacobid::test::run_command(std::string(JACOBID_EXECUTABLE) + " " + args); }

// Per joint q = pose + a [(1 - cos wt) - (1 - cos 2wt) / 4] + b [(1 - cos 3wt) - 9 (1 - cos 4wt) / 16]:
// periodic, at rest at t = 0 with zero acceleration (so the simulated robot, which starts at rest there,
// follows it from the first period on), four harmonics.
std::string trajectory() {
    const std::string file = path("period_traj.csv");
    if (std::filesystem::exists(file)) return file;
    const double w = 2.0 * kPi / kPeriod;
    const double pose[2] = {0.2, 0.9}, a[2] = {0.8, -0.6}, b[2] = {0.3, 0.4};
    std::ofstream out(file);
    out << "t,q1,q2,qd1,qd2,qdd1,qdd2\n";
    out.precision(17);
    const int rows = static_cast<int>(kPeriod * 1000.0);
    for (int k = 0; k <= rows; ++k) {
        const double t = k * 1e-3;
        double q[2], qd[2], qdd[2];
        for (int j = 0; j < 2; ++j) {
            q[j] = pose[j] + a[j] * ((1 - std::cos(w * t)) - (1 - std::cos(2 * w * t)) / 4) + b[j] * ((1 - std::cos(3 * w * t)) - 9 * (1 - std::cos(4 * w * t)) / 16);
            qd[j] = a[j] * (w * std::sin(w * t) - 2 * w * std::sin(2 * w * t) / 4) + b[j] * (3 * w * std::sin(3 * w * t) - 9 * 4 * w * std::sin(4 * w * t) / 16);
            qdd[j] = a[j] * (w * w * std::cos(w * t) - 4 * w * w * std::cos(2 * w * t) / 4) +
                     b[j] * (9 * w * w * std::cos(3 * w * t) - 9 * 16 * w * w * std::cos(4 * w * t) / 16);
        }
        out << t << ',' << q[0] << ',' << q[1] << ',' << qd[0] << ',' << qd[1] << ',' << qdd[0] << ',' << qdd[1] << '\n';
    }
    return file;
}

std::string robot() {
    std::ofstream(path("period_robot.yaml")) << "model: planar2r\nL1: 0.5\nfriction: {coulomb: smooth, alpha: 100}\n";
    return path("period_robot.yaml");
}

// Five periods of the trajectory, with the main job's noise; returns the log (truth beside it).
std::string periodic_log() {
    const std::string log = path("periodic.csv");
    if (std::filesystem::exists(log)) return log;
    const auto r = jacobid_cli("simulate --quiet --robot " + robot() + " --trajectory " + trajectory() + " --duration " +
                               std::to_string(kPeriod * kPeriods) + " --encoder-counts 65536 --torque-noise 0.05,0.01 --seed 1 --noise-seed 7 -o " +
                               log + " --truth " + path("periodic.truth.json"));
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return log;
}

json identify(const std::string& extra) {
    const auto r = jacobid_cli("identify --quiet --format json --robot " + robot() + " --in " + periodic_log() + " " + extra);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return r.exit_code == 0 ? json::parse(r.out) : json();
}

TEST(PeriodicIdentify, PeriodIsFoundAndTheSpreadIsTheSimulatedNoise) {
    const json j = identify("--period auto");
    ASSERT_TRUE(j.contains("period")) << j.dump().substr(0, 400);
    const json& p = j["period"];
    EXPECT_TRUE(p["detected"].get<bool>());
    EXPECT_EQ(p["samples"].get<int>(), static_cast<int>(kPeriod * 1000.0)) << p.dump();
    EXPECT_NEAR(p["seconds"].get<double>(), kPeriod, 1e-9);
    EXPECT_EQ(p["periods"].get<int>(), kPeriods);
    // The simulated robot starts at rest and settles during the first period (its positions differ from the
    // later, identical periods by ~4e-5 rad RMS): that period is left out, and said so.
    EXPECT_EQ(p["skipped_periods"].dump(), "[1]");
    EXPECT_EQ(p["averaged_periods"].get<int>(), kPeriods - 1);
    ASSERT_EQ(p["warnings"].size(), 1u) << p.dump();
    EXPECT_NE(p["warnings"][0].get<std::string>().find("period(s) 1 of 5 not averaged"), std::string::npos) << p.dump();
    EXPECT_EQ(p["wrap_jump"].dump(), "[0.0,0.0]") << "the later periods repeat exactly, so the mean period closes";
    // The spread of 4000 x 4 samples about their mean: the noise within ~2 % (plus what the closed loop
    // adds, which is small at this encoder resolution).
    for (int k = 0; k < 2; ++k) EXPECT_NEAR(p["torque_noise"][k].get<double>(), kNoise[k], 0.1 * kNoise[k]) << "joint " << k + 1 << ": " << p.dump();
    // The weights are the noise's: joint 2 weighs 5 x joint 1.
    const json& weights = j["joint_weights"];
    EXPECT_NEAR(weights[1].get<double>() / weights[0].get<double>(), kNoise[0] / kNoise[1], 0.1 * kNoise[0] / kNoise[1]) << weights.dump();
    // Given, the same period gives the same numbers.
    const json given = identify("--period 4");
    EXPECT_FALSE(given["period"]["detected"].get<bool>());
    EXPECT_EQ(given["parameters"].dump(), j["parameters"].dump());
}

// The periodic log with a 1 s ramp from 0 to its first pose in front (what jacobid-fw's playback records):
// the start that is no period must neither move the period found nor enter the mean.
std::string ramped_log() {
    const std::string file = path("ramped.csv");
    std::ifstream in(periodic_log());
    std::ofstream out(file);
    out.precision(17);
    std::string header, first;
    std::getline(in, header);
    std::getline(in, first);
    out << header << '\n';
    std::vector<double> cells;
    std::stringstream ss(first);
    for (std::string c; std::getline(ss, c, ',');) cells.push_back(std::stod(c));
    const int ramp = 1000;
    for (int k = 0; k < ramp; ++k) {
        const double u = static_cast<double>(k) / ramp, s = u * u * u * (10 - 15 * u + 6 * u * u);
        out << k * 1e-3 << ',' << cells[1] * s << ',' << cells[2] * s;
        for (std::size_t c = 3; c < cells.size(); ++c) out << ',' << cells[c];
        out << '\n';
    }
    // The periodic rows after it, their times shifted by the ramp's second.
    int row = ramp;
    auto shifted = [&](const std::string& line) { out << (row++) * 1e-3 << line.substr(line.find(',')) << '\n'; };
    shifted(first);
    for (std::string line; std::getline(in, line);) shifted(line);
    return file;
}

TEST(PeriodicIdentify, ARampBeforeThePeriodsNeitherMovesThePeriodNorEntersTheMean) {
    const auto r = jacobid_cli("identify --quiet --format json --robot " + robot() + " --in " + ramped_log() + " --period auto");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const json p = json::parse(r.out)["period"];
    EXPECT_EQ(p["samples"].get<int>(), static_cast<int>(kPeriod * 1000.0)) << "the whole-log minimum alone was 4002" << p.dump();
    EXPECT_EQ(p["skipped_periods"].dump(), "[1]") << p.dump();
    for (int k = 0; k < 2; ++k) EXPECT_NEAR(p["torque_noise"][k].get<double>(), kNoise[k], 0.1 * kNoise[k]) << p.dump();
}

TEST(PeriodicIdentify, MeanPeriodIdentifiesTheTruthWithHonestStd) {
    const json j = identify("--period auto --truth " + path("periodic.truth.json"));
    std::ifstream in(path("periodic.truth.json"));
    json truth;
    in >> truth;
    int checked = 0;
    for (const auto& name : j["parameter_order"]) {
        const std::string n = name.get<std::string>();
        const json& p = j["parameters"][n];
        if (!p["identified"].get<bool>() || !truth["parameters"].contains(n)) continue;
        const double x = p["value"].get<double>(), s = p["std"].get<double>(), t = truth["parameters"][n].get<double>();
        EXPECT_LT(std::abs(x - t), 4.0 * s + 1e-3 * std::abs(t)) << n << ": " << x << " against " << t << " (std " << s << ")";
        EXPECT_LT(std::abs(x - t), 0.02 * std::abs(t) + 1e-3) << n << ": " << x << " against " << t;
        ++checked;
    }
    EXPECT_GE(checked, 6);
    // One period's worth of equations (the mean period's middle copy), not four, and none lost at the edges:
    // about 4 s / (decimated sample period).
    const double decimated_period = j["settings"]["decimation"].get<double>() * 1e-3;
    EXPECT_NEAR(j["equations"].get<double>() / 2.0, kPeriod / decimated_period, 2.0) << j["settings"].dump();
}

TEST(PeriodicIdentify, BadPeriodsAreRefusedWithOneLine) {
    const std::string base = "identify --quiet --robot " + robot() + " --in " + periodic_log();
    struct Case {
        std::string option, expected;
    };
    for (const Case& c : {Case{"--period 4.0005", "not a whole number"}, Case{"--period 12", "at least two whole periods"},
                          Case{"--period abc", "expected auto or a period in seconds"}, Case{"--period -1", "expected auto or a period in seconds"},
                          Case{"--period auto --estimator didim", "--period with --estimator didim"}}) {
        const auto r = jacobid_cli(base + " " + c.option);
        EXPECT_EQ(r.exit_code, 2) << c.option << ": " << r.err;
        EXPECT_NE(r.err.find(c.expected), std::string::npos) << c.option << ": " << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    }
    // A log of random moves does not repeat.
    const std::string random = path("random.csv");
    ASSERT_EQ(jacobid_cli("simulate --quiet --robot " + robot() + " --duration 20 --seed 3 -o " + random).exit_code, 0);
    const auto r = jacobid_cli("identify --quiet --robot " + robot() + " --in " + random + " --period auto");
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("do not repeat"), std::string::npos) << r.err;
}

}  // namespace
