// SPDX-License-Identifier: MIT
// jacobid monitor on a simulated 6-axis arm (the UR5-like description, torque noise 0.5 to 0.1 N.m), issue
// 40's acceptance: with the model identified from a simulated run (identify --export-robot), external torque
// pulses on each joint (simulate --effect external:...) detected within 20 ms and their amplitude within
// 10 %, no alarm on contact-free runs of the same length. The reference is the simulation's own truth, the
// tau_ext columns the simulator logs beside the measured ones (never the monitor's output).
// Also: simulate's contact shapes against their definition, and the one-line refusals of bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "io/csv_table.hpp"
#include "command_cache.hpp"
#include "run_command.hpp"
#include "scratch_directory.hpp"

namespace {

namespace fs = std::filesystem;
using jacobid::test::run_command;

const std::string kJacobid = JACOBID_EXECUTABLE;
const std::string kRobot = std::string(JACOBID_TESTS_DIR) + "/../examples/robots/ur5_like.yaml";
// The estimator a 1 kHz controller would run: Jacobi windows of 40 ms evaluated half-way (10 ms delay).
const std::string kCalibration = " --velocity-window 0.04 --xi 0.5 --standing-velocity 0.05 --false-alarm-rate 0 --margin 0.5";

std::string scratch(const std::string& name) { return jacobid::test::scratch_file("monitor", name).string(); }

// The runs the monitor is tested on; their simulator is fixture_executable()'s (tests/support/command_cache.hpp).
std::string simulate_command(const std::string& out, int seed, const std::string& effects = "", double duration = 20.0) {
    return jacobid::test::fixture_executable(kJacobid) + " simulate --robot " + kRobot + " --out " + out + " --duration " + std::to_string(duration) + " --seed " + std::to_string(seed) +
           " --noise-seed " + std::to_string(seed + 100) + " --torque-noise 0.5,0.5,0.3,0.1,0.1,0.1 --quiet" + effects;
}

void simulate(const std::string& out, int seed, const std::string& effects = "", double duration = 20.0) {
    const auto r = run_command(simulate_command(out, seed, effects, duration));
    ASSERT_EQ(r.exit_code, 0) << r.err;
}

// The model the monitor runs: identified from a 60 s simulated run, as identify --export-robot writes it. Made
// once for every test process (tests/support/command_cache.hpp): each case runs in a process of its own.
const std::string& identified_robot() {
    static const std::string robot = [] {
        const auto c = jacobid::test::cached_command(simulate_command("{dir}/train.csv", 21, "", 60.0) + " && " + kJacobid + " identify --robot " + kRobot +
                                                         " --in {dir}/train.csv --export-robot {dir}/identified.yaml --quiet",
                                                     kJacobid, {kRobot});
        EXPECT_EQ(c.result.exit_code, 0) << c.result.err;
        return (c.dir / "identified.yaml").string();
    }();
    return robot;
}

// Contact-free calibration runs, shared by the tests of this program (simulated once for every test process).
const std::string& calibrated_monitor() {
    static const std::string monitor = [] {
        std::string command, ins;
        for (int seed = 1; seed <= 5; ++seed) {
            const std::string log = "{dir}/free" + std::to_string(seed) + ".csv";
            command += simulate_command(log, seed) + " && ";
            ins += " --in " + log;
        }
        command += kJacobid + " monitor calibrate --robot " + identified_robot() + ins + " --out {dir}/monitor.yaml" + kCalibration;
        const auto c = jacobid::test::cached_command(command, kJacobid, {kRobot, identified_robot()});
        EXPECT_EQ(c.result.exit_code, 0) << c.result.err;
        return (c.dir / "monitor.yaml").string();
    }();
    return monitor;
}

nlohmann::json monitor_events(const std::string& log) {
    const auto r = run_command(kJacobid + " monitor --robot " + identified_robot() + " --monitor " + calibrated_monitor() + " --in " + log + " --json");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return nlohmann::json::parse(r.out)["events"];
}

struct TruePulse {
    int joint = 0;  // 1-based
    double onset = 0.0, value = 0.0;
};

// The pulses as the simulator logged them: each joint's first sample with a non-zero tau_ext.
std::vector<TruePulse> logged_pulses(const std::string& log) {
    const jacobid::io::CsvTable table = jacobid::io::read_csv(log);
    std::vector<TruePulse> pulses;
    for (int j = 1; j <= 6; ++j) {
        const auto& truth = table.column("tau_ext" + std::to_string(j));
        for (std::size_t i = 0; i < truth.size(); ++i) {
            if (truth[i] != 0.0) {
                pulses.push_back({j, table.column("t")[i], truth[i]});
                break;
            }
        }
    }
    return pulses;
}

TEST(MonitorSimulatedArm, PulsesOnEveryJointAreDetectedWithin20msAndTheirAmplitudeWithin10Percent) {
    // About four times each joint's calibrated moving threshold (0.2 N.m on the wrists to 4 on the shoulder).
    const std::string log = scratch("pulses.csv");
    simulate(log, 7,
             " --effect external:joint=1,start=2,duration=0.5,value=10 --effect external:joint=2,start=5,duration=0.5,value=20"
             " --effect external:joint=3,start=8,duration=0.5,value=-10 --effect external:joint=4,start=11,duration=0.5,value=4"
             " --effect external:joint=5,start=14,duration=0.5,value=3 --effect external:joint=6,start=17,duration=0.5,value=-2");
    const std::vector<TruePulse> pulses = logged_pulses(log);
    ASSERT_EQ(pulses.size(), 6u);
    const nlohmann::json events = monitor_events(log);
    EXPECT_EQ(events.size(), pulses.size()) << events.dump(1);
    for (const TruePulse& p : pulses) {
        const nlohmann::json* found = nullptr;
        for (const auto& e : events) {
            const auto& joints = e["joints"];
            if (std::find(joints.begin(), joints.end(), p.joint) != joints.end() && e["start"].get<double>() >= p.onset - 1e-9 &&
                e["start"].get<double>() < p.onset + 0.5) {
                found = &e;
            }
        }
        ASSERT_NE(found, nullptr) << "joint " << p.joint << " pulse at " << p.onset << " s not reported: " << events.dump(1);
        const double delay = (*found)["start"].get<double>() - p.onset;
        const double level = (*found)["median"][static_cast<std::size_t>(p.joint - 1)].get<double>();
        EXPECT_LE(delay, 0.020) << "joint " << p.joint;
        EXPECT_NEAR(level, p.value, 0.10 * std::abs(p.value)) << "joint " << p.joint;
        std::cout << "joint " << p.joint << ": " << p.value << " N.m detected after " << 1e3 * delay << " ms, level " << level << " N.m ("
                  << 100.0 * (level - p.value) / p.value << " %)\n";
    }
}

TEST(MonitorSimulatedArm, ContactFreeRunsOfTheSameLengthRaiseNoAlarm) {
    for (int seed = 11; seed <= 13; ++seed) {
        const std::string log = scratch("check" + std::to_string(seed) + ".csv");
        simulate(log, seed);
        EXPECT_TRUE(monitor_events(log).empty()) << "seed " << seed << ": " << monitor_events(log).dump(1);
    }
}

TEST(SimulateExternal, ShapesFollowTheirDefinitionInTheLoggedTruth) {
    const std::string log = scratch("shapes.csv");
    simulate(log, 3, " --effect external:joint=2,start=0.5,duration=0.4,value=8,shape=sine --effect external:joint=3,start=1.0,duration=0.5,value=-6,shape=ramp", 2.0);
    const jacobid::io::CsvTable table = jacobid::io::read_csv(log);
    const auto& t = table.column("t");
    const auto& sine = table.column("tau_ext2");
    const auto& ramp = table.column("tau_ext3");
    for (std::size_t i = 0; i < t.size(); ++i) {
        const double s2 = (t[i] - 0.5) / 0.4, s3 = (t[i] - 1.0) / 0.5;
        EXPECT_NEAR(sine[i], s2 >= 0 && s2 < 1 ? 8.0 * std::sin(M_PI * s2) : 0.0, 1e-9) << t[i];
        EXPECT_NEAR(ramp[i], s3 >= 0 && s3 < 1 ? -6.0 * s3 : 0.0, 1e-9) << t[i];
        EXPECT_EQ(table.column("tau_ext1")[i], 0.0);
    }
}

TEST(MonitorRefusals, BadInputIsOneLineNamingWhatWasExpected) {
    const std::string free = scratch("refusal_free.csv");
    simulate(free, 2, "", 1.0);
    struct Case {
        std::string args, expected;
    };
    const std::string bad_yaml = jacobid::test::write_scratch_file("monitor", "bad.yaml", "joints:\n  - {moving: 1, standing: 0.5}\n");
    std::string six = "joints:\n  - {moving: 1, standing: 0.5}\n  - {moving: -1, standing: 0.5}\n";
    for (int j = 3; j <= 6; ++j) six += "  - {moving: 1, standing: 0.5}\n";
    const std::string negative = jacobid::test::write_scratch_file("monitor", "negative.yaml", six);
    const std::vector<Case> cases = {
        {" monitor --robot " + kRobot + " --in " + free, "needs --robot, --monitor and --in"},
        {" monitor --robot " + kRobot + " --monitor " + bad_yaml + " --in " + free, "bad.yaml:2:3: joints: must be a list of 6"},
        {" monitor --robot " + kRobot + " --monitor " + negative + " --in " + free, "negative.yaml:3:14: joints[1].moving: must be >= 0"},
        {" monitor --robot " + kRobot + " --monitor " + scratch("missing.yaml") + " --in " + free, "missing.yaml"},
        {" monitor calibrate --robot " + kRobot + " --in " + free + " --out " + scratch("m.yaml") + " --false-alarm-rate 1.5", "--false-alarm-rate"},
        {" monitor calibrate --robot " + kRobot + " --in " + free + " --out " + scratch("m.yaml") + " --estimator kalman", "--estimator"},
        {" monitor calibrate --robot " + kRobot + " --in " + free + " --out " + scratch("m.yaml") + " --band-margin -1", "--band-margin"},
        {" monitor calibrate --robot " + kRobot + " --in " + free + " --out " + scratch("m.yaml") + " --band-margin 0.1,0.2", "--band-margin: 2 values for 6 joints"},
        {" simulate --robot " + kRobot + " --out " + scratch("x.csv") + " --effect external:joint=2,start=1,value=3", "external needs 'duration'"},
        {" simulate --robot " + kRobot + " --out " + scratch("x.csv") + " --effect external:joint=2,start=1,duration=1,value=nan", "'nan' is not a finite number"},
    };
    for (const Case& c : cases) {
        const auto r = run_command(kJacobid + c.args);
        EXPECT_NE(r.exit_code, 0) << c.args;
        EXPECT_NE(r.err.find(c.expected), std::string::npos) << c.args << "\n" << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    }
}

}  // namespace
