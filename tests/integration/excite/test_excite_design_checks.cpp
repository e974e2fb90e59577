// SPDX-License-Identifier: MIT
// Issue 36: an excitation design that means nothing is refused, never written with exit 0. Before, excite
// --velocity-limit 1e-9 "designed" a 1e-10 rad motion with cond 1.8e16, and a 1e12-sample period was blamed on
// --rate. The rules (excite/design_checks.hpp) directly, then the command line.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "cli_refusal.hpp"
#include "core/errors.hpp"
#include "excite/design_checks.hpp"
#include "excite_test_support.hpp"
#include "run_command.hpp"
#include "scratch_directory.hpp"

namespace {

using namespace jacobid;
using test::expect_refused;
using test::kTwoLink;

std::string error_of(const std::function<void()>& f) {
    try {
        f();
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

TEST(ExciteDesignChecks, EachJointNeedsRoomToMoveAtTheBaseFrequency) {
    excite::JointLimits l;
    l.lower = -1.0, l.upper = 1.0, l.velocity = 2.0, l.acceleration = 10.0;
    const Eigen::VectorXd pose = Eigen::VectorXd::Zero(2);
    EXPECT_EQ(error_of([&] { excite::require_room_to_move({l, l}, pose, 0.2, "the robot description"); }), "");
    excite::JointLimits slow = l;
    slow.velocity = 2.0 * M_PI * 0.2 * 0.999e-3;  // an amplitude just below 1 mrad at 0.2 Hz
    EXPECT_NE(error_of([&] { excite::require_room_to_move({l, slow}, pose, 0.2, "x"); })
                  .find("--velocity-limit: joint 2's 0.00125538 rad/s allows a motion of at most v / (2 pi f0) = 0.000999 rad"),
              std::string::npos);
    slow.velocity = 2.0 * M_PI * 0.2 * 1.001e-3;
    EXPECT_EQ(error_of([&] { excite::require_room_to_move({l, slow}, pose, 0.2, "x"); }), "");
    excite::JointLimits gentle = l;
    gentle.acceleration = 1e-9;
    EXPECT_NE(error_of([&] { excite::require_room_to_move({gentle, l}, pose, 0.2, "x"); }).find("--acceleration-limit: joint 1's 1e-09 rad/s^2"), std::string::npos);
    Eigen::VectorXd edge = pose;
    edge[0] = 0.9995;
    EXPECT_NE(error_of([&] { excite::require_room_to_move({l, l}, edge, 0.2, "--position-limit"); }).find("--pose: joint 1 at 0.9995 is 0.0005 from its limit"),
              std::string::npos);
}

TEST(ExciteDesignChecks, ADesignThatCannotSeparateTheBaseParametersIsRefused) {
    excite::Design d;
    d.cond = 1.25e16;
    d.check.worst = 0.493, d.check.worst_joint = 1, d.check.worst_kind = excite::LimitKind::Velocity;
    EXPECT_NE(error_of([&] { excite::require_separable_design(d); }).find("the best design found has cond 1.25e+16"), std::string::npos);
    EXPECT_NE(error_of([&] { excite::require_separable_design(d); }).find("joint 2's velocity limit"), std::string::npos);
    d.cond = 90.0;
    EXPECT_EQ(error_of([&] { excite::require_separable_design(d); }), "");
}

test::CommandResult excite_cli(const std::string& args) {
    return test::run_command(std::string(JACOBID_EXECUTABLE) + " excite --quiet --robot " + kTwoLink + " --starts 1 --time-limit 5 -o " +
                             (test::scratch_directory() / "design_checks.csv").string() + " " + args);
}

TEST(ExciteDesignChecks, TheCommandRefusesLimitsWithoutRoomAndNamesTheBaseFrequencyForItsPeriod) {
    expect_refused(excite_cli("--duration 10 --base-frequency 0.2 --velocity-limit 1e-9"),
                   {"--velocity-limit: joint 1's 1e-09 rad/s allows a motion of at most v / (2 pi f0) = 7.96e-10 rad"});
    expect_refused(excite_cli("--base-frequency 1e-9 --duration 1e9"),
                   {"--base-frequency 1e-09 Hz: a period of 1e+09 s is 1e+12 samples at --rate 1000 Hz, more than the 1e+08"});
    expect_refused(excite_cli("--duration 1e-3"), {"the automatic base frequency 2000 Hz (--duration 0.001 s in 2 periods): a period of 0.0005 s holds 0.5 "
                                                   "samples at --rate 1000 Hz, fewer than 2 x 3 harmonics + 1 = 7"});
}

// --max-evaluations: runs that stop on their evaluation budget, not on the time, give the same design again (the
// starts draw from --seed, whatever the threads), and the budget bounds the evaluations the JSON reports: each start
// and each tightening round runs the optimizer at most 3 times (a run that stalls restarts from its best iterate).
TEST(ExciteDesignChecks, AnEvaluationBudgetGivesTheSameDesignAgainAndBoundsTheEvaluations) {
    const auto design = [](const std::string& name, const std::string& threads) {
        const std::string csv = (test::scratch_directory() / (name + ".csv")).string(), json = (test::scratch_directory() / (name + ".json")).string();
        const auto r = test::run_command(std::string(JACOBID_EXECUTABLE) + " excite --quiet --robot " + kTwoLink +
                                         " --duration 10 --velocity-limit 2 --acceleration-limit 8 --starts 3 --time-limit 600 --max-evaluations 40 --threads " +
                                         threads + " -o " + csv + " --json " + json);
        EXPECT_EQ(r.exit_code, 0) << r.err;
        std::ifstream in(csv);
        std::stringstream text;
        text << in.rdbuf();
        return std::make_pair(text.str(), nlohmann::json::parse(std::ifstream(json)));
    };
    const auto [one, one_json] = design("budget_one_thread", "1");
    const auto [two, two_json] = design("budget_two_threads", "2");
    EXPECT_FALSE(one.empty());
    EXPECT_EQ(one, two);
    const int rounds = one_json["tightening_rounds"].get<int>();
    EXPECT_LE(one_json["evaluations"].get<int>(), 40 * 3 * (3 + rounds));
    EXPECT_GT(one_json["evaluations"].get<int>(), 3);  // every start evaluated
    expect_refused(excite_cli("--max-evaluations 0"), {"--max-evaluations: expected a whole number in [1, 1e+09], got '0'"});
}

}  // namespace
