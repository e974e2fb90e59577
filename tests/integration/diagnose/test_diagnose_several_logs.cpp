// SPDX-License-Identifier: MIT
// `jacobid diagnose --in a.csv --in b.csv` (issue 18): several logs diagnosed together. The hidden effect is
// named from the simulator's truth, the nominal identification equals identify's own stacking of the same
// logs (its --in a --in b path, OLS, no delay), and a log at another sample period is refused by name.
#include <gtest/gtest.h>

#include <cmath>

#include "diagnose_test_support.hpp"

namespace jacobid::test {
namespace {

const char* const kCogging = "cogging:joint=2,amplitude=0.15,order=6,phase=40";

TEST(DiagnoseSeveralLogs, NamesTheEffectAndIdentifiesTheNominalModelAsIdentifyStacksTheLogs) {
    const std::string a = scratch("several_a.csv"), b = scratch("several_b.csv"), truth = scratch("several_a.truth.json");
    ASSERT_EQ(simulate_log(a, 15, 41, std::string("--truth ") + truth + " --effect " + kCogging).exit_code, 0);
    ASSERT_EQ(simulate_log(b, 12, 42, std::string("--effect ") + kCogging).exit_code, 0);
    const auto r = run_command(std::string(JACOBID_EXECUTABLE) + " diagnose --robot " + diagnose_robot_yaml() + " --in " + a + " --in " + b +
                               " --format json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto d = nlohmann::json::parse(r.out);
    EXPECT_EQ(d["logs"].size(), 2u);
    EXPECT_EQ(d["logs"][1], b);
    ASSERT_GE(d["effects"].size(), 1u) << r.out;
    EXPECT_EQ(d["effects"][0]["name"], "cogging");
    EXPECT_EQ(d["effects"][0]["joint"], 2);
    const double injected = read_json(truth)["effects"].at(0)["value"].get<double>();
    EXPECT_NEAR(d["effects"][0]["value"].get<double>(), injected, 0.2 * injected);
    // Both logs' short-horizon segments (0.5 s apart by default): more than one log alone has.
    EXPECT_GT(d["before"]["horizon_segments"].get<int>(), 40);

    // identify --in a --in b: the same plan (resolved on the longer log), rows and equations.
    const auto id = run_command(std::string(JACOBID_EXECUTABLE) + " identify --robot " + diagnose_robot_yaml() + " --in " + a + " --in " + b +
                                " --weighting ols --torque-delay 0 --format json");
    ASSERT_EQ(id.exit_code, 0) << id.err;
    const auto i = nlohmann::json::parse(id.out);
    std::size_t rows = 0;
    for (const auto& s : i["segments"]) rows += s["rows"].get<std::size_t>();
    EXPECT_EQ(d["rows"].get<std::size_t>(), rows);
    for (const auto& [name, value] : d["before"]["parameters"].items()) {
        const double expected = i["parameters"][name]["value"].get<double>();
        EXPECT_NEAR(value.get<double>(), expected, 1e-10 * std::abs(expected)) << name;
    }
}

// A 3 s log has fewer equations than the catalogue has columns: refused alone, it adds its rows beside a
// longer log (the count is checked on the stack).
TEST(DiagnoseSeveralLogs, AShortLogAddsItsRowsToALongerOne) {
    const std::string long_log = scratch("stack_long.csv"), short_log = scratch("stack_short.csv");
    ASSERT_EQ(simulate_log(long_log, 15, 61, "").exit_code, 0);
    ASSERT_EQ(simulate_log(short_log, 3, 62, "").exit_code, 0);
    const std::string diagnose = std::string(JACOBID_EXECUTABLE) + " diagnose --quiet --format json --robot " + diagnose_robot_yaml();
    const auto alone = run_command(diagnose + " --in " + short_log);
    EXPECT_EQ(alone.exit_code, 2);
    EXPECT_NE(alone.err.find("the log is too short"), std::string::npos) << alone.err;
    const auto first = run_command(diagnose + " --in " + long_log), both = run_command(diagnose + " --in " + long_log + " --in " + short_log);
    ASSERT_EQ(first.exit_code, 0) << first.err;
    ASSERT_EQ(both.exit_code, 0) << both.err;
    EXPECT_GT(nlohmann::json::parse(both.out)["rows"].get<std::size_t>(), nlohmann::json::parse(first.out)["rows"].get<std::size_t>());
}

TEST(DiagnoseSeveralLogs, ALogAtAnotherSamplePeriodIsRefusedByName) {
    const std::string a = scratch("period_a.csv"), b = scratch("period_b.csv");
    ASSERT_EQ(simulate_log(a, 8, 51, "").exit_code, 0);
    ASSERT_EQ(simulate_log(b, 8, 52, "--rate 500").exit_code, 0);
    const auto r = run_command(std::string(JACOBID_EXECUTABLE) + " diagnose --robot " + diagnose_robot_yaml() + " --in " + a + " --in " + b);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("--in " + b + ": sample period"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "one line: " << r.err;
}

}  // namespace
}  // namespace jacobid::test
