// SPDX-License-Identifier: MIT
// End-to-end acceptance of `jacobid simulate` + `jacobid identify`: the expected values are the truth of
// the simulation (the paper's Table II, which the simulator integrates through its own forward dynamics),
// never numbers copied from the identifier's output.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "simulated_log.hpp"
#include "identification_bars.hpp"
#include "run_command.hpp"
#include "scratch_directory.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

using CliRun = jacobid::test::CommandResult;

fs::path work_dir() { return jacobid::test::scratch_directory(); }

std::string slurp(const fs::path& p) {
    std::ifstream in(p);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

CliRun jacobid(const std::string& args) { return jacobid::test::run_command(std::string(JACOBID_EXECUTABLE) + " " + args); }

std::string path(const std::string& name) { return (work_dir() / name).string(); }

void write(const std::string& name, const std::string& text) { std::ofstream(work_dir() / name) << text; }

const char* kRobot = "model: planar2r\nL1: 0.5\nfriction: {coulomb: smooth, alpha: 100}\n";

// Simulates once per log name and arguments for all the test processes (tests/support/simulated_log.hpp:
// each case runs in a process of its own, and five read noisy1k); copies the log and its truth here and
// returns the log's path.
std::string simulate(const std::string& name, const std::string& args) {
    const std::string log = path(name + ".csv");
    if (!fs::exists(log)) {
        const auto r = jacobid::test::simulated_log(log, "--quiet " + args);
        EXPECT_EQ(r.exit_code, 0) << r.err;
    }
    return log;
}

json identify_json(const std::string& log, const std::string& args) {
    write("robot.yaml", kRobot);
    const CliRun r = jacobid("identify --robot " + path("robot.yaml") + " --in " + log + " --format json " + args);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return json::parse(r.out);
}

// Relative error of parameter `name` against the paper's Table II (the simulator's default truth).
const std::string kNoisy = "--duration 30 --encoder-counts 65536 --torque-noise 0.05,0.01 --seed 7 --noise-seed 8";

TEST(IdentifyAcceptance, Jacobi1kHzAutomaticWindows) {
    const json j = identify_json(simulate("noisy1k", kNoisy + " --rate 1000"), "--method jacobi");
    jacobid::test::expect_table2_bars(j);
    EXPECT_TRUE(j["settings"]["bandwidth_estimated"].get<bool>());
    EXPECT_EQ(j["unidentifiable"].size(), 0u);
    // The paper's experiment has cond(W) = 38; random quintic moves excite the model comparably well.
    EXPECT_LT(j["cond"].get<double>(), 100.0);
    for (const auto& name : j["parameter_order"]) {
        const auto& p = j["parameters"][name.get<std::string>()];
        EXPECT_GT(p["std"].get<double>(), 0.0);
        EXPECT_NEAR(p["rel_std_percent"].get<double>(), 100.0 * p["std"].get<double>() / std::abs(p["value"].get<double>()), 1e-9);
    }
}

TEST(IdentifyAcceptance, Jacobi100HzSameTrajectory) {
    const json j = identify_json(simulate("noisy100", kNoisy + " --rate 100"), "--method jacobi");
    // Reported figures (docs/performance.md and the final report): same tolerances hold at 100 Hz.
    jacobid::test::expect_table2_bars(j);
}

TEST(IdentifyAcceptance, NoiseFreeDataRecoversEveryParameter) {
    // Unquantized, noise-free; the simulator's friction and the regressor both use 2/pi atan(100 qd).
    const std::string log = simulate("clean", "--duration 30 --encoder-counts 0 --seed 11");
    const json j = identify_json(log, "--method jacobi --cutoff 40");
    const std::pair<const char*, double> truth[] = {{"ZZ1R", 3.496}, {"FV1", 0.248}, {"FC1", 0.431},  {"ZZ2", 0.059},
                                                    {"MX2", 0.124},  {"MY2", 0.0019}, {"FV2", 0.0144}, {"FC2", 0.1268}};
    for (const auto& [name, value] : truth) {
        const double x = j["parameters"][name]["value"].get<double>();
        EXPECT_TRUE(std::abs(x - value) <= 1e-3 * std::abs(value) || std::abs(x - value) <= 1e-5) << name << " = " << x << ", truth " << value;
    }
}

TEST(IdentifyAcceptance, ButterworthSideBySideAndTruthColumn) {
    const std::string log = simulate("noisy1k", kNoisy + " --rate 1000");
    write("robot.yaml", kRobot);
    const CliRun r = jacobid("identify --robot " + path("robot.yaml") + " --in " + log + " --method both --truth " + path("noisy1k.truth.json"));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("Jacobi"), std::string::npos);
    EXPECT_NE(r.out.find("Butterworth"), std::string::npos);
    EXPECT_NE(r.out.find("cond(W)"), std::string::npos);
    EXPECT_NE(r.out.find("relative error norm"), std::string::npos);
    const json j = identify_json(log, "--method butterworth");
    EXPECT_LT(jacobid::test::relative_error(j, "ZZ1R", 3.496), 0.01);
    EXPECT_LT(jacobid::test::relative_error(j, "MX2", 0.124), 0.01);
}

// Scripts read "methods.<name>" whatever --method; the top level repeats the first method (as single-method
// output always had it).
TEST(IdentifyAcceptance, JsonLayoutIsTheSameWithOneMethodOrBoth) {
    const std::string log = simulate("noisy1k", kNoisy + " --rate 1000");
    const json one = identify_json(log, "--method butterworth");
    const json both = identify_json(log, "--method both");
    ASSERT_TRUE(one.contains("methods"));
    EXPECT_EQ(one["methods"].size(), 1u);
    EXPECT_EQ(one["methods"]["butterworth"]["parameters"], one["parameters"]);
    EXPECT_EQ(both["methods"].size(), 2u);
    EXPECT_EQ(both["methods"]["butterworth"]["parameters"], one["parameters"]);
    EXPECT_EQ(both["methods"]["jacobi"]["parameters"], both["parameters"]);
    for (const json* j : {&one, &both}) {
        for (const char* key : {"parameters", "warnings", "plausibility_violations", "torque_delay", "settings", "log", "model"}) {
            EXPECT_TRUE(j->contains(key)) << key;
        }
    }
}

TEST(IdentifyAcceptance, ValidationOnASecondTrajectoryIsWithinTwiceTheNoise) {
    const std::string log = simulate("noisy1k", kNoisy + " --rate 1000");
    const std::string other = simulate("other1k", "--duration 20 --encoder-counts 65536 --torque-noise 0.05,0.01 --seed 99 --noise-seed 98");
    const json j = identify_json(log, "--validate " + other);
    const auto rms = j["validation"]["rms_error"];
    EXPECT_LT(rms[0].get<double>(), 2 * 0.05);
    EXPECT_LT(rms[1].get<double>(), 2 * 0.01);
    // rms_error compares after the identification's decimation filter (as Y vs W X^); the raw full-rate
    // error also carries the noise itself, which no model predicts.
    EXPECT_GT(j["validation"]["raw_rms_error"][0].get<double>(), 0.05);
    EXPECT_LT(j["validation"]["relative_error"].get<double>(), 0.02);
}

// When the torque's band widens the differentiators (bandwidth.hpp), the raw full-rate comparison still
// differentiates at the motion's own band (10 x the velocity's): at full rate nothing filters the acceleration
// noise the wider band lets in. An explicit --cutoff is used as given.
TEST(IdentifyAcceptance, RawValidationDifferentiatesAtTheMotionsOwnBand) {
    const std::string log = simulate("noisy1k", kNoisy + " --rate 1000");
    const std::string other = simulate("other1k", "--duration 20 --encoder-counts 65536 --torque-noise 0.05,0.01 --seed 99 --noise-seed 98");
    const json automatic = identify_json(log, "--validate " + other);
    const json& settings = automatic["settings"];
    ASSERT_TRUE(settings["bandwidth_estimate"]["torque_wider"].get<bool>()) << "this log no longer widens the differentiators: pick another";
    const double motion_cutoff = 10.0 * settings["bandwidth_hz"].get<double>();
    const double cutoff = settings["differentiator_cutoff_hz"].get<double>();
    ASSERT_GT(cutoff, 1.2 * motion_cutoff);
    EXPECT_NEAR(automatic["validation"]["raw_differentiator_cutoff_hz"].get<double>(), motion_cutoff, 1e-9 * motion_cutoff);
    // The same fit compared at full rate through the wide differentiators carries more noise on joint 1.
    const json wide = identify_json(log, "--validate " + other + " --cutoff " + std::to_string(cutoff));
    EXPECT_NEAR(wide["validation"]["raw_differentiator_cutoff_hz"].get<double>(), cutoff, 1e-6 * cutoff);
    EXPECT_GT(wide["validation"]["raw_rms_error"][0].get<double>(), 1.5 * automatic["validation"]["raw_rms_error"][0].get<double>());
    // The filtered comparison is the identification's own, through the wide differentiators either way.
    EXPECT_NEAR(wide["validation"]["rms_error"][0].get<double>(), automatic["validation"]["rms_error"][0].get<double>(),
                0.05 * automatic["validation"]["rms_error"][0].get<double>());
}

TEST(IdentifyAcceptance, WeightedAndEssentialParameters) {
    const std::string log = simulate("noisy1k", kNoisy + " --rate 1000");
    const json w = identify_json(log, "--weighted");
    EXPECT_TRUE(w["weighted"].get<bool>());
    // Gautier's weights are 1 / sigma_j: joint 2 (noise 0.01) weighs more than joint 1 (noise 0.05).
    EXPECT_GT(w["joint_weights"][1].get<double>(), w["joint_weights"][0].get<double>());
    EXPECT_LT(jacobid::test::relative_error(w, "ZZ1R", 3.496), 0.01);
    // Threshold 0.5 %: MY2 (true value 0.0019, tiny contribution) has the largest %sigma_r and goes first. With
    // the default WLS and joint-hac std its %sigma_r is 0.70 % (the pooled OLS figure was 1.37 %; the
    // 40-run spread of docs/method.md "Bias and standard deviations, measured" is 0.73 %), the next FV2 0.22 %.
    const json e = identify_json(log, "--essential 0.5");
    ASSERT_GE(e["essential"]["steps"].size(), 2u);
    EXPECT_EQ(e["essential"]["steps"][1]["removed"], "MY2");
    EXPECT_TRUE(e["essential"]["final"]["MY2"]["removed"].get<bool>());
}

// --joint-noise: the WLS weights are 1 / the given noise (the simulation's own), not the residuals' sigma, and
// the fit still finds the truth; a noise per joint is required, and it contradicts OLS.
TEST(IdentifyAcceptance, JointNoiseGivesTheWeights) {
    const std::string log = simulate("noisy1k", kNoisy + " --rate 1000");
    const json w = identify_json(log, "--joint-noise 0.05,0.01");
    EXPECT_TRUE(w["weighted"].get<bool>());
    EXPECT_NEAR(w["joint_weights"][0].get<double>(), 1.0 / 0.05, 1e-9);
    EXPECT_NEAR(w["joint_weights"][1].get<double>(), 1.0 / 0.01, 1e-9);
    EXPECT_LT(jacobid::test::relative_error(w, "ZZ1R", 3.496), 0.01);
    write("robot.yaml", kRobot);
    const CliRun one = jacobid("identify --robot " + path("robot.yaml") + " --in " + log + " --joint-noise 0.05");
    EXPECT_NE(one.exit_code, 0);
    EXPECT_NE(one.err.find("--joint-noise needs one value per joint: 1 given for 2 joints"), std::string::npos) << one.err;
    const CliRun ols = jacobid("identify --robot " + path("robot.yaml") + " --in " + log + " --joint-noise 0.05,0.01 --weighting ols");
    EXPECT_NE(ols.exit_code, 0);
    EXPECT_NE(ols.err.find("--joint-noise"), std::string::npos) << ols.err;
}

TEST(IdentifyAcceptance, ReportWritesMarkdownAndPlots) {
    const std::string log = simulate("short1k", "--duration 8 --torque-noise 0.05,0.01");
    write("robot.yaml", kRobot);
    const CliRun r = jacobid("identify --robot " + path("robot.yaml") + " --in " + log + " --method both --report " + path("report"));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(fs::exists(path("report/report.md")));
    EXPECT_GT(fs::file_size(path("report/torque_jacobi.png")), 1000u);
    EXPECT_GT(fs::file_size(path("report/torque_butterworth.png")), 1000u);
}

// Rewrites column `col` of a CSV log with a constant (a joint that never moves).
std::string freeze_column(const std::string& log, const std::string& name, const std::vector<int>& cols) {
    std::ifstream in(log);
    std::ofstream out(path(name));
    std::string line;
    std::getline(in, line);
    out << line << "\n";
    while (std::getline(in, line)) {
        std::vector<std::string> cells;
        std::stringstream ss(line);
        for (std::string c; std::getline(ss, c, ',');) cells.push_back(c);
        for (int c : cols) cells[static_cast<std::size_t>(c)] = "0.3";
        for (std::size_t i = 0; i < cells.size(); ++i) out << (i ? "," : "") << cells[i];
        out << "\n";
    }
    return path(name);
}

TEST(IdentifyBadInput, JointThatNeverMovesIsReportedNotFitted) {
    const std::string log = freeze_column(simulate("short1k", "--duration 8 --torque-noise 0.05,0.01"), "frozen2.csv", {2});
    write("robot.yaml", kRobot);
    const CliRun r = jacobid("identify --robot " + path("robot.yaml") + " --in " + log + " --format json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("joint 2"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("FV2 cannot be identified"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("FC2 cannot be identified"), std::string::npos) << r.err;
    const json j = json::parse(r.out);
    EXPECT_FALSE(j["parameters"]["FV2"]["identified"].get<bool>());
    EXPECT_TRUE(j["parameters"]["FV2"]["value"].is_null());
    // With q2 constant, ZZ1R, ZZ2, MX2, MY2 enter through 3 independent columns only: one null combination.
    EXPECT_EQ(j["rank"].get<int>(), 5);
    EXPECT_EQ(j["unidentifiable"].size(), 3u);
}

TEST(IdentifyBadInput, RobotStandingStillIsAnError) {
    const std::string log = freeze_column(simulate("short1k", "--duration 8 --torque-noise 0.05,0.01"), "frozen.csv", {1, 2});
    write("robot.yaml", kRobot);
    const CliRun r = jacobid("identify --robot " + path("robot.yaml") + " --in " + log);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("stands still"), std::string::npos) << r.err;
}

TEST(IdentifyBadInput, UnknownModelMissingColumnNaNAndShortLog) {
    write("bad_model.yaml", "model: scara9\n");
    const std::string log = simulate("short1k", "--duration 8 --torque-noise 0.05,0.01");
    CliRun r = jacobid("identify --robot " + path("bad_model.yaml") + " --in " + log);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("bad_model.yaml:1:8: model: 'scara9' is not one of: planar2r, mdh, urdf"), std::string::npos) << r.err;

    write("robot.yaml", kRobot);
    write("missing.csv", "t,q1,q2,tau1\n0,0,0,0\n0.001,0,0,0\n");
    r = jacobid("identify --robot " + path("robot.yaml") + " --in " + path("missing.csv"));
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("no column 'tau2'"), std::string::npos) << r.err;

    write("nan.csv", "t,q1,q2,tau1,tau2\n0,0,0,0,0\n0.001,nan,0,0,0\n");
    r = jacobid("identify --robot " + path("robot.yaml") + " --in " + path("nan.csv"));
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("nan.csv:3: column 'q1'"), std::string::npos) << r.err;

    // 0.3 s of motion cannot hold windows plus the decimation filter's end transients.
    const std::string tiny = simulate("tiny", "--duration 0.3");
    r = jacobid("identify --robot " + path("robot.yaml") + " --in " + tiny + " --bandwidth 2");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("too short"), std::string::npos) << r.err;
}

TEST(SimulateCli, WritesHeaderRowsTruthAndHelp) {
    const std::string log = simulate("rate100", "--duration 2 --rate 100");
    std::ifstream in(log);
    std::string header;
    std::getline(in, header);
    // The measured columns, then the reference the controller tracked (for --estimator iv | didim).
    EXPECT_EQ(header, "t,q1,q2,tau1,tau2,q_ref1,q_ref2,qd_ref1,qd_ref2");
    std::size_t rows = 0;
    for (std::string l; std::getline(in, l);) ++rows;
    EXPECT_EQ(rows, 201u);
    const json truth = json::parse(slurp(path("rate100.truth.json")));
    EXPECT_DOUBLE_EQ(truth["parameters"]["ZZ1R"].get<double>(), 3.496);
    EXPECT_DOUBLE_EQ(truth["parameters"]["MY2"].get<double>(), 0.0019);
    EXPECT_EQ(jacobid("simulate --help").exit_code, 0);
    EXPECT_EQ(jacobid("identify --help").exit_code, 0);
    const CliRun bad = jacobid("simulate --out " + path("x.csv") + " --rate 300");
    EXPECT_EQ(bad.exit_code, 2);
    EXPECT_NE(bad.err.find("--rate"), std::string::npos);
}

}  // namespace
