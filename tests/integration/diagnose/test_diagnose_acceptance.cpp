// SPDX-License-Identifier: MIT
// Acceptance of `jacobid diagnose` (issue 7) on simulated data in which the simulator hides an effect from
// the nominal model. Ground truth comes from the simulator's truth JSON, never from the diagnosis.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>

#include "diagnose_test_support.hpp"

namespace jacobid::test {
namespace {

struct EffectCase {
    const char* name;    // effect name as the issue spells it
    const char* effect;  // --effect token
    int joint;           // 1-based, 0 for whole-robot effects
};

// Realistic magnitudes (docs/diagnose.md): offset 0.2 N.m; asymmetry 0.1 N.m = 23 % of FC1 = 0.431; Stribeck
// 0.3 N.m above Coulomb at vs = 0.09 rad/s (between the search grid points 0.08 and 0.1); qd|qd| 0.01 (0.04-0.09 N.m at the moves' 2-3
// rad/s); base tilted 3 deg with 1.5 kg m on link 1; cogging 0.15 N.m at 6 per rev; rotor inertia
// 0.05 kg m^2 on joint 2 (joint 1's regroups into ZZ1R); torque channel 3 ms late; presliding friction (a Dahl
// state, issue 15) of 0.3 N.m on joint 1 at x_p = 6e-4 rad (between the search grid points 4e-4 and 8e-4); 0.3 N.m
// of joint 1's Coulomb friction at a smoothing alpha of 20 s/rad beside the description's 100 (issue 15). On a grid
// point: between two, the level of the nearest one trades off with FC1 (0.40 N.m named at 40 for 0.3 injected at
// 30); at 40 the effect differs from the nominal friction only near reversals and its held-out gap (-45 %) is
// close to the noise floor.
const EffectCase kCases[] = {
    {"coulomb_offset", "coulomb_offset:joint=1,value=0.2", 1},
    {"coulomb_asymmetry", "coulomb_asymmetry:joint=1,value=0.1", 1},
    {"stribeck", "stribeck:joint=1,value=0.3,velocity=0.09", 1},
    {"viscous_nonlinear", "viscous_nonlinear:joint=2,value=0.01", 2},
    {"gravity", "gravity:tilt=3,direction=30,mx1=1.5", 0},
    {"cogging", "cogging:joint=2,amplitude=0.15,order=6,phase=40", 2},
    {"rotor_inertia", "rotor_inertia:joint=2,value=0.05", 2},
    {"torque_delay", "torque_delay:value=0.003", 0},
    {"presliding", "presliding:joint=1,value=0.3,displacement=6e-4", 1},
    {"coulomb_smoothing", "coulomb_smoothing:joint=1,value=0.3,alpha=20", 1},
};

// gtest prints parameters in ctest's test names; the effect name reads better than the bytes.
void PrintTo(const EffectCase& c, std::ostream* os) { *os << c.effect; }

// Held-out RMS of the affected joint, or over all joints for whole-robot effects.
double heldout(const nlohmann::json& side, int joint) {
    const auto rms = side["heldout_rms"].get<std::vector<double>>();
    if (joint > 0) return rms.at(static_cast<std::size_t>(joint - 1));
    double s = 0.0;
    for (double r : rms) s += r * r;
    return std::sqrt(s);
}

class EachEffectAlone : public ::testing::TestWithParam<EffectCase> {};

TEST_P(EachEffectAlone, IsNamedFirstWithinTwentyPercentAndHalvesTheHeldOutError) {
    const EffectCase& c = GetParam();
    const std::string log = scratch(std::string(c.name) + ".csv"), val = scratch(std::string(c.name) + ".val.csv");
    const std::string truth = scratch(std::string(c.name) + ".truth.json");
    ASSERT_EQ(simulate_log(log, 30, 11, std::string("--truth ") + truth + " --effect " + c.effect).exit_code, 0);
    ASSERT_EQ(simulate_log(val, 20, 12, std::string("--effect ") + c.effect).exit_code, 0);
    const auto r = run_command(std::string(JACOBID_EXECUTABLE) + " diagnose --robot " + diagnose_robot_yaml() + " --in " + log + " --validate " +
                               val + " --format json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("diagnose: "), std::string::npos) << "progress on stderr";
    const auto d = nlohmann::json::parse(r.out);
    const auto injected = read_json(truth)["effects"].at(0);
    ASSERT_GE(d["effects"].size(), 1u) << r.out;
    const auto& first = d["effects"][0];
    EXPECT_EQ(first["name"], c.name);
    if (c.joint > 0) {
        EXPECT_EQ(first["joint"], c.joint);
    } else {
        EXPECT_TRUE(first["joint"].is_null());
    }
    const double truth_value = injected["value"].get<double>();
    EXPECT_NEAR(first["value"].get<double>(), truth_value, 0.2 * std::abs(truth_value)) << first.dump();
    EXPECT_GT(first["std"].get<double>(), 0.0);
    // The hyper-parameter found on its grid next to the truth's (factor-2 grids: within a factor 2).
    for (const char* key : {"displacement", "alpha"}) {
        if (!injected.contains(key)) continue;
        ASSERT_TRUE(first.contains(key)) << first.dump();
        EXPECT_LT(std::abs(std::log(first[key].get<double>() / injected[key].get<double>())), std::log(2.0) + 1e-9) << key << ' ' << first.dump();
    }
    const double before = heldout(d["before"], c.joint), after = heldout(d["after"], c.joint);
    EXPECT_LE(after, 0.5 * before) << "held-out RMS " << before << " -> " << after;
    // The short-horizon simulation error of the affected joint(s) shrinks too.
    const auto hb = d["before"]["horizon_rms"].get<std::vector<double>>(), ha = d["after"]["horizon_rms"].get<std::vector<double>>();
    double sb = 0.0, sa = 0.0;
    for (std::size_t j = 0; j < hb.size(); ++j) {
        if (c.joint > 0 && static_cast<int>(j) != c.joint - 1) continue;
        sb += hb[j] * hb[j];
        sa += ha[j] * ha[j];
    }
    EXPECT_LT(sa, sb);
}

INSTANTIATE_TEST_SUITE_P(Diagnose, EachEffectAlone, ::testing::ValuesIn(kCases),
                         [](const ::testing::TestParamInfo<EffectCase>& p) { return std::string(p.param.name); });

TEST(Diagnose, AWrongCoulombSmoothingIsNamedAsSuchNotAbsorbedByStribeckTerms) {
    // Issue 15: the truth's Coulomb friction is smoothed at alpha 100 s/rad, the description says 20. The
    // diagnosis names the smoothing on both joints (grid points next to 100), no Stribeck term, and the
    // held-out error of each joint falls by more than half.
    const std::string log = scratch("alpha_truth100.csv"), val = scratch("alpha_truth100.val.csv"), wrong = scratch("robot_alpha20.yaml");
    ASSERT_EQ(simulate_log(log, 30, 41, "").exit_code, 0);
    ASSERT_EQ(simulate_log(val, 20, 42, "").exit_code, 0);
    std::ifstream in(diagnose_robot_yaml());
    std::string yaml((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::size_t at = yaml.find("alpha: 100");
    ASSERT_NE(at, std::string::npos);
    yaml.replace(at, 10, "alpha: 20");
    std::ofstream(wrong) << yaml;
    const auto r = run_command(std::string(JACOBID_EXECUTABLE) + " diagnose --quiet --robot " + wrong + " --in " + log + " --validate " + val +
                               " --format json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto d = nlohmann::json::parse(r.out);
    ASSERT_GE(d["effects"].size(), 2u) << d["effects"].dump();
    std::set<int> joints;
    for (const auto& e : d["effects"]) {
        EXPECT_NE(e["name"], "stribeck") << e.dump();
        if (e["name"] != "coulomb_smoothing") continue;
        joints.insert(e["joint"].get<int>());
        const double alpha = e["alpha"].get<double>();
        EXPECT_TRUE(alpha >= 40.0 && alpha <= 320.0) << e.dump();  // within a factor ~3 of the truth's 100
    }
    EXPECT_EQ(joints, (std::set<int>{1, 2}));
    for (int joint : {1, 2}) EXPECT_LE(heldout(d["after"], joint), 0.5 * heldout(d["before"], joint)) << "joint " << joint;
}

TEST(Diagnose, TwoEffectsTogetherAreBothNamedWithCrossValidation) {
    const std::string log = scratch("two.csv");
    ASSERT_EQ(simulate_log(log, 30, 31, "--effect coulomb_offset:joint=1,value=0.2 --effect cogging:joint=2,amplitude=0.15,order=8").exit_code, 0);
    const auto r = run_command(std::string(JACOBID_EXECUTABLE) + " diagnose --robot " + diagnose_robot_yaml() + " --in " + log + " --format json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto d = nlohmann::json::parse(r.out);
    bool offset = false, cogging = false;
    for (const auto& e : d["effects"]) {
        offset = offset || (e["name"] == "coulomb_offset" && e["joint"] == 1);
        cogging = cogging || (e["name"] == "cogging" && e["joint"] == 2 && e["order"] == 8);
    }
    EXPECT_TRUE(offset) << d["effects"].dump();
    EXPECT_TRUE(cogging) << d["effects"].dump();
    EXPECT_EQ(d["effects"].size(), 2u) << d["effects"].dump();
    EXPECT_NE(d["selection"]["heldout"].get<std::string>().find("cross-validation"), std::string::npos);
}

class CleanData : public ::testing::TestWithParam<int> {};

TEST_P(CleanData, NamesNothing) {
    const int seed = GetParam();
    const std::string log = scratch("clean" + std::to_string(seed) + ".csv");
    ASSERT_EQ(simulate_log(log, 30, seed, "").exit_code, 0);
    const auto r = run_command(std::string(JACOBID_EXECUTABLE) + " diagnose --robot " + diagnose_robot_yaml() + " --in " + log + " --format json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto d = nlohmann::json::parse(r.out);
    EXPECT_TRUE(d["effects"].empty()) << d["effects"].dump();
    EXPECT_NE(d["verdict"].get<std::string>().find("no effect named"), std::string::npos);
}

INSTANTIATE_TEST_SUITE_P(Diagnose, CleanData, ::testing::Values(21, 22, 23, 24, 25));

TEST(Diagnose, WeakEffectBelowTheNoiseFloorIsNotNamedAndTheReportSaysSo) {
    // 0.002 N.m offset on joint 1: a tenth of joint 1's filtered residual floor (~0.022 N.m with 0.05 N.m
    // torque noise), half the standard deviation an offset estimate has on 30 s.
    const std::string log = scratch("weak.csv"), report = scratch("weak-report");
    ASSERT_EQ(simulate_log(log, 30, 32, "--effect coulomb_offset:joint=1,value=0.002").exit_code, 0);
    const auto r = run_command(std::string(JACOBID_EXECUTABLE) + " diagnose --robot " + diagnose_robot_yaml() + " --in " + log + " --report " + report);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("Named effects:\n  none"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("no effect named"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("noise floor"), std::string::npos) << r.out;
    std::ifstream md(report + "/report.md");
    std::stringstream text;
    text << md.rdbuf();
    EXPECT_NE(text.str().find("noise floor"), std::string::npos);
    for (const char* png : {"residual_velocity.png", "residual_position.png"}) {
        EXPECT_GT(std::filesystem::file_size(report + "/" + png), 1000u) << png;
    }
}

TEST(Diagnose, BadInputIsAOneLineErrorWithExitStatusTwo) {
    const std::string log = scratch("bad.csv");
    std::ofstream(log) << "t,q1,q2,tau1\n0,0,0,0\n0.001,0,0,0\n";
    const auto r = run_command(std::string(JACOBID_EXECUTABLE) + " diagnose --robot " + diagnose_robot_yaml() + " --in " + log);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("tau2"), std::string::npos) << r.err;
    const auto help = run_command(std::string(JACOBID_EXECUTABLE) + " diagnose --help");
    EXPECT_EQ(help.exit_code, 0);
    EXPECT_NE(help.out.find("--validate"), std::string::npos);
}

}  // namespace
}  // namespace jacobid::test
