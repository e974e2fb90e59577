// SPDX-License-Identifier: MIT
// Issue 20 ("Bad input, round two"): the examples an audit found still failing after the first rounds. Each
// is a one-line error with exit status 2 naming the file, line, column, key or option (or, for a capture's
// bounded jitter, a correct result); docs/reliability.md, "Bad input, round two: the rest".
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli_refusal.hpp"
#include "run_command.hpp"
#include "scratch_directory.hpp"

namespace {

namespace fs = std::filesystem;
using jacobid::test::expect_refused;
using jacobid::test::run_command;
using json = nlohmann::json;

jacobid::test::CommandResult jacobid(const std::string& args) { return run_command("timeout 60 " + std::string(JACOBID_EXECUTABLE) + " " + args); }

fs::path scratch(const std::string& name) {
    const fs::path dir = jacobid::test::scratch_directory() / "bad_input_rest";
    fs::create_directories(dir);
    return dir / name;
}

std::string write(const std::string& name, const std::string& text) {
    const fs::path p = scratch(name);
    std::ofstream(p, std::ios::binary) << text;
    return p.string();
}

const auto read = jacobid::test::read_text;

void expect_refused_on_one_line(const jacobid::test::CommandResult& r, std::initializer_list<std::string> words) {
    expect_refused(r, words);
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "not one line: " << r.err;
}

std::vector<std::string> lines_of(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string l; std::getline(in, l);) lines.push_back(l);
    return lines;
}

std::string joined(const std::vector<std::string>& lines) {
    std::string s;
    for (const auto& l : lines) s += l + "\n";
    return s;
}

// The planar 2R with its joint limits (+-2.5 rad), as the main job's robot.yaml.
const std::string& planar_robot() {
    static const std::string p = write("planar.yaml", "model: planar2r\nL1: 0.5\njoints:\n  - {name: j1, position: q1, torque: tau1, limits: [-2.5, 2.5]}\n"
                                                      "  - {name: j2, position: q2, torque: tau2, limits: [-2.5, 2.5]}\n");
    return p;
}

// A valid log of that robot (t, q1, q2, tau1, tau2, q_ref.., qd_ref..) and its truth file, made once.
const std::string& planar_log() {
    static const std::string path = [] {
        const std::string p = scratch("planar.csv").string();
        const auto r = jacobid("simulate --robot " + planar_robot() + " --duration 8 --torque-noise 0.05,0.01 --quiet -o " + p + " --truth " +
                               scratch("planar.truth.json").string());
        EXPECT_EQ(r.exit_code, 0) << r.err;
        return p;
    }();
    return path;
}

// The log with data row `row` (0-based), column `column` (0-based) replaced.
std::string log_with_cell(const std::string& name, std::size_t row, std::size_t column, const std::string& value) {
    std::vector<std::string> lines = lines_of(read(planar_log()));
    std::string& line = lines.at(row + 1);
    std::size_t start = 0;
    for (std::size_t c = 0; c < column; ++c) start = line.find(',', start) + 1;
    const std::size_t end = line.find(',', start);
    line = line.substr(0, start) + value + (end == std::string::npos ? "" : line.substr(end));
    return write(name, joined(lines));
}

// --- 1. A --log-format log whose time step is 1e200 s ---------------------------------------------------

TEST(CliBadInputRest, LogFormatTimeStepOf1e200IsNamedByEveryCommandThatReadsLogs) {
    // No header, t = 0, 1e200, 2e200, ... (the time column was exempt from the 1e30 bound on values): before,
    // exit 2 blaming the Jacobi window ("too short for the window of a 3.9e-203 Hz cutoff").
    const std::vector<std::string> lines = lines_of(read(planar_log()));
    std::ostringstream raw;
    raw.precision(17);
    for (std::size_t k = 1; k < 3000; ++k) raw << static_cast<double>(k - 1) * 1e200 << lines[k].substr(lines[k].find(',')) << "\n";
    const std::string log = write("huge_step.csv", raw.str());
    const std::string format = write("huge_step.yaml", "header: false\ntime: {column: 1}\npositions: [2, 3]\ntorques: [4, 5]\n");
    const std::string in = " --log-format " + format + " --in " + log;
    for (const std::string& command : {"identify --robot " + planar_robot() + in, "diagnose --robot " + planar_robot() + in,
                                       "differentiate -c q1 --cutoff 10" + in}) {
        const auto r = jacobid(command);
        // Issue 36: times are bounded like every value (+-1e30), so the row is bad before its step is measured.
        expect_refused(r, {"huge_step.csv:2: column 1 (time): value 1e+200 is beyond +-1e30"});
        EXPECT_EQ(r.err.find("window"), std::string::npos) << r.err;
    }
    std::ostringstream within;
    within.precision(17);
    for (std::size_t k = 1; k < 3000; ++k) within << static_cast<double>(k - 1) * 1e20 << lines[k].substr(lines[k].find(',')) << "\n";
    expect_refused(jacobid("identify --robot " + planar_robot() + " --log-format " + format + " --in " + write("step_1e20.csv", within.str())),
                   {"step_1e20.csv: time column 1: the median time step is 1e+20 s, outside the plausible sample periods"});
    // A plain CSV log is bounded alike (its steps of 1e20 s are within the 1e30 value bound).
    std::ostringstream csv;
    csv << "t,q1,q2,tau1,tau2\n";
    for (int k = 0; k < 3000; ++k) csv << k << "e20," << std::sin(0.01 * k) << ",0,0,0\n";
    expect_refused_on_one_line(jacobid("differentiate -c q1 --cutoff 10 --in " + write("csv_step.csv", csv.str())),
                               {"csv_step.csv: column 't': the median time step is 1e+20 s"});
}

// --- 2. Duplicate output columns of differentiate ------------------------------------------------------

TEST(CliBadInputRest, DifferentiateRefusesOutputColumnsItWouldWriteTwice) {
    const std::string out = scratch("d.csv").string();
    expect_refused_on_one_line(jacobid("differentiate --in " + planar_log() + " -c q1,q1 --cutoff 10 -o " + out),
                               {"--columns: 'q1' is given twice (entries 1 and 2)"});
    expect_refused_on_one_line(jacobid("differentiate --in " + planar_log() + " -c q1,q2 --orders 2,1,2 --cutoff 10 -o " + out),
                               {"--orders: order 2 is given twice (entries 1 and 3), which would write the column 'q1_d2' twice"});
    EXPECT_FALSE(fs::exists(out));
    // Distinct columns and orders: written, and read back by jacobid's own CSV reader (differentiating its output).
    ASSERT_EQ(jacobid("differentiate --in " + planar_log() + " -c q1,q2 --orders 1,2 --cutoff 10 -o " + out).exit_code, 0);
    EXPECT_EQ(lines_of(read(out)).front(), "t,q1_d1,q1_d2,q2_d1,q2_d2");
    EXPECT_EQ(jacobid("differentiate --in " + out + " -c q1_d1 --orders 1 --cutoff 10 -o " + scratch("dd.csv").string()).exit_code, 0);
}

// --- 3. A truth file of another robot ------------------------------------------------------------------

TEST(CliBadInputRest, TruthOfAnotherRobotOrParameterSetIsRefused) {
    planar_log();
    const std::string own = scratch("planar.truth.json").string();
    const std::string identify = "identify --quiet --robot " + planar_robot() + " --in " + planar_log() + " --truth ";
    ASSERT_EQ(jacobid(identify + own).exit_code, 0);
    json truth = json::parse(read(own));
    // A PUMA's parameters given for the planar 2R: before, accepted with +814 % "errors".
    json puma = truth;
    puma["parameters"] = {{"XX1", 0.0}, {"ZZ1R", 1.2}, {"MX2", 0.3}};
    expect_refused_on_one_line(jacobid(identify + write("puma.truth.json", puma.dump())), {"puma.truth.json: no parameter 'FV1'", "the truth of another robot"});
    json missing = truth;
    missing["parameters"].erase("ZZ2");
    expect_refused_on_one_line(jacobid(identify + write("missing.truth.json", missing.dump())), {"no parameter 'ZZ2', which the robot description"});
    json extra = truth;
    extra["parameters"]["IA2"] = 0.01;  // the parameter set of a robot with rotor_inertia: true
    expect_refused_on_one_line(jacobid(identify + write("extra.truth.json", extra.dump())), {"parameter 'IA2' is not one of the robot description"});
}

// --- 4. A position outlier -----------------------------------------------------------------------------

TEST(CliBadInputRest, PositionOutsideTheJointLimitsNamesFileLineColumnValueAndLimit) {
    // One cell of 50 rad where the limits are +-2.5 rad: before, exit 0 with only a friction warning.
    const std::string log = log_with_cell("outlier.csv", 4000, 1, "50");
    for (const char* command : {"identify", "diagnose"}) {
        expect_refused_on_one_line(jacobid(std::string(command) + " --quiet --robot " + planar_robot() + " --in " + log),
                                   {"outlier.csv:4002: column 'q1': position 50 is outside joint 1 (j1)'s limits [-2.5, 2.5] by more than their range 5"});
    }
    // Within the limits plus the tolerance (their range, 5 rad): accepted, as real logs that pass their limits are.
    EXPECT_EQ(jacobid("identify --quiet --robot " + planar_robot() + " --in " + log_with_cell("near.csv", 4000, 1, "3.1")).exit_code, 0);
    // A robot without limits is not checked against invented defaults.
    const std::string free_robot = write("free.yaml", "model: planar2r\nL1: 0.5\n");
    EXPECT_EQ(jacobid("identify --quiet --robot " + free_robot + " --in " + log).err.find("is outside joint"), std::string::npos);
    // Read with a --log-format (raw lines), the raw line and column are named.
    const std::string format = write("outlier.yaml", "header: true\ntime: {column: t}\npositions: [q1, q2]\ntorques: [tau1, tau2]\n");
    expect_refused_on_one_line(jacobid("identify --quiet --robot " + planar_robot() + " --log-format " + format + " --in " + log),
                               {"outlier.csv:4002: column 2 (positions[0]): position 50 is outside joint 1 (j1)'s limits"});
}

// --- 5. Gear ratio and offset of a CAN config ----------------------------------------------------------

const char* kFirmwareConfig =
    "can: {interface: can0}\n"
    "joints:\n"
    "  - {name: shoulder, profile: mit, motor_id: 1, gear_ratio: 4, velocity_range: [-65, 65], effort_range: [-30, 30]}\n"
    "  - {name: elbow, profile: mit, motor_id: 2, gear_ratio: 4, velocity_range: [-65, 65], effort_range: [-2, 2]}\n"
    "stream: {host: 127.0.0.1, port: 5005}\n";

std::string config_with(const std::string& name, const std::string& from, const std::string& to) {
    std::string text = kFirmwareConfig;
    text.replace(text.find(from), from.size(), to);
    return write(name, text);
}

// A capture of the planar 2R through kFirmwareConfig's MIT drivers, made once.
const std::string& capture() {
    static const std::string path = [] {
        const std::string p = scratch("capture.log").string();
        const auto r = jacobid("sim-can --robot " + planar_robot() + " --config " + write("fw.yaml", kFirmwareConfig) + " --candump " + p +
                               " --duration 12 --seed 4 --quiet");
        EXPECT_EQ(r.exit_code, 0) << r.err;
        return p;
    }();
    return path;
}

TEST(CliBadInputRest, GearRatioAndOffsetOfACanConfigAreBoundedAndNamed) {
    const std::string ratio = config_with("ratio.yaml", "gear_ratio: 4,", "gear_ratio: 1e308,");
    const std::string offset = config_with("offset.yaml", "gear_ratio: 4,", "gear_ratio: 4, offset: 1e308,");
    const std::string out = scratch("unused.log").string();
    // Before: identify named a key that is not in the file (or read every frame as out of range), sim-can exited 0.
    expect_refused_on_one_line(jacobid("identify --robot " + planar_robot() + " --can-config " + ratio + " --in " + capture()),
                               {"ratio.yaml:3:", "joints[0].gear_ratio: gear ratio must be of magnitude 1e-06 to 1e+06 (motor turns per link turn)"});
    expect_refused_on_one_line(jacobid("sim-can --robot " + planar_robot() + " --config " + ratio + " --candump " + out + " --duration 0.1"),
                               {"ratio.yaml:3:", "joints[0].gear_ratio"});
    for (const std::string& command : {"identify --robot " + planar_robot() + " --can-config " + offset + " --in " + capture(),
                                       "sim-can --robot " + planar_robot() + " --config " + offset + " --candump " + out + " --duration 0.1"}) {
        expect_refused_on_one_line(jacobid(command), {"offset.yaml:3:", "joints[0].offset: position offset must be a finite number within +-10000"});
    }
    EXPECT_FALSE(fs::exists(out));
}

// --- 6. Receive-time jitter of a candump capture -------------------------------------------------------

// The capture with every cycle's stamps (both frames of a cycle) moved by jitter(cycle) microseconds.
template <typename Jitter>
std::string jittered(const std::string& name, const std::vector<std::string>& lines, Jitter jitter) {
    std::string out;
    for (std::size_t i = 0; i < lines.size(); ++i) {
        const std::string& l = lines[i];
        const std::size_t dot = l.find('.'), close = l.find(')');
        long long us = std::stoll(l.substr(1, dot - 1)) * 1000000 + std::stoll(l.substr(dot + 1, close - dot - 1)) + jitter(i / 2);
        char stamp[40];
        std::snprintf(stamp, sizeof stamp, "(%lld.%06lld)", us / 1000000, us % 1000000);
        out += stamp + l.substr(close + 1) + "\n";
    }
    return write(name, out);
}

// Uniform in [-300, 300] us, a fixed sequence.
long long jitter_us(std::size_t cycle) {
    std::uint64_t x = (cycle + 1) * 0x9E3779B97F4A7C15ull;
    x ^= x >> 31;
    x *= 0xBF58476D1CE4E5B9ull;
    x ^= x >> 29;
    return static_cast<long long>(x % 601) - 300;
}

TEST(CliBadInputRest, CaptureJitterWithinTheToleranceUsesTheNominalCycleAndIsReported) {
    const std::vector<std::string> lines = lines_of(read(capture()));
    const std::string fw = write("fw.yaml", kFirmwareConfig);
    const std::string identify = "identify --robot " + planar_robot() + " --can-config " + fw + " --format json --in ";
    const auto clean = jacobid(identify + capture());
    ASSERT_EQ(clean.exit_code, 0) << clean.err;
    // +-0.3 ms at a 1 ms cycle: before, refused by the 1 % time-step check.
    const auto r = jacobid(identify + jittered("jitter.log", lines, jitter_us));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("time stamps within +-0.3"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("ms of a 1 ms cycle (receive-time jitter): the nominal cycle used"), std::string::npos) << r.err;
    // The same samples on the same grid: the same identification as from the capture without jitter.
    const json a = json::parse(clean.out), b = json::parse(r.out);
    for (const auto& [name, p] : a["parameters"].items()) {
        EXPECT_NEAR(b["parameters"][name]["value"].get<double>(), p["value"].get<double>(), 1e-6 * (1.0 + std::abs(p["value"].get<double>()))) << name;
    }
    // A lost cycle (both frames of cycle 4000 deleted, lines 8001-8002) is still refused with its line.
    std::vector<std::string> lost = lines;
    lost.erase(lost.begin() + 8000, lost.begin() + 8002);
    auto calm_near_the_gap = [](std::size_t c) { return c >= 3990 && c <= 4010 ? 0 : jitter_us(c); };
    expect_refused_on_one_line(jacobid(identify + jittered("lost_cycle.log", lost, calm_near_the_gap)),
                               {"lost_cycle.log:8001: the cycle beginning on this line is", "2 ms after the cycle on line 7999", "a lost cycle"});
    // Stamps that go back: named by line.
    auto back = [](std::size_t c) { return c == 3000 ? -1500LL : 0LL; };
    expect_refused_on_one_line(jacobid(identify + jittered("back.log", lines, back)), {"back.log:6001: the cycle beginning on this line is stamped",
                                                                                       "(time must increase)"});
    // Jitter beyond +-0.4 cycle: refused, not smoothed over.
    auto wild = [](std::size_t c) { return c == 5000 ? 450LL : 0LL; };
    expect_refused_on_one_line(jacobid(identify + jittered("wild.log", lines, wild)), {"wild.log:10001: the cycle beginning on this line is 0.45 ms off"});
}

// --- 7. Invisible characters, NUL bytes and huge tokens in messages ------------------------------------

TEST(CliBadInputRest, QuotedUserTextIsEscapedAndBounded) {
    std::string text = read(planar_log());
    text.replace(text.find("q1"), 2, "q1\xE2\x80\x8B");  // a zero-width space after q1 in the header
    auto r = jacobid("identify --robot " + planar_robot() + " --in " + write("zwsp.csv", text));
    expect_refused_on_one_line(r, {"no column 'q1' (columns: t,q1\\u200b,q2,"});
    EXPECT_EQ(r.err.find("\xE2\x80\x8B"), std::string::npos);
    r = jacobid("identify --robot " + planar_robot() + " --in " + write("nul.csv", std::string("t,q1,q2,tau1,tau2\n0,0,0,0,0\n0.001,0\0x\x1b,0,0,0\n", 45)));
    expect_refused_on_one_line(r, {"nul.csv:3: column 'q1': expected a number, got '0\\0x\\x1b'"});
    // A 700 000-character token: quoted as its first 80 characters (before: a 689 KB error line).
    r = jacobid("identify --robot " + planar_robot() + " --in " + write("huge.csv", "t,q1,q2,tau1,tau2\n0,0,0,0," + std::string(700000, 'x') + "\n"));
    expect_refused_on_one_line(r, {"column 'tau2': expected a number, got '" + std::string(80, 'x') + "...'"});
    EXPECT_LT(r.err.size(), 300u);
    // Anywhere else (a robot's column name, an option's value), the message as a whole is bounded.
    r = jacobid("identify --robot " + planar_robot() + " --in " + planar_log() + " --method " + std::string(100000, 'm'));
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_LT(r.err.size(), 2200u) << r.err.size();
    EXPECT_NE(r.err.find("characters left out"), std::string::npos);
}

// --- 8. --report checked before the work ---------------------------------------------------------------

TEST(CliBadInputRest, ReportDirectoryIsCheckedBeforeTheWork) {
    // A log that fails only after reading (an outlier): the report's refusal must come first.
    const std::string log = log_with_cell("late.csv", 4000, 1, "50");
    expect_refused_on_one_line(jacobid("identify --robot " + planar_robot() + " --in " + log + " --report /proc/x/report"),
                               {"--report /proc/x/report: cannot create the directory"});
    expect_refused_on_one_line(jacobid("diagnose --robot " + planar_robot() + " --in " + log + " --report " + planar_log()),
                               {"--report " + planar_log() + ": exists and is not a directory"});
    // A directory that can be made is not left behind by the check when the work then fails.
    const fs::path fresh = scratch("fresh") / "report";
    fs::remove_all(scratch("fresh"));
    EXPECT_EQ(jacobid("identify --robot " + planar_robot() + " --in " + log + " --report " + fresh.string()).exit_code, 2);
    EXPECT_FALSE(fs::exists(scratch("fresh")));
}

}  // namespace

// --- 7. Found by the audit of 2026-12-03 ---------------------------------------------------------------

namespace {

// Injected effects of absurd size: before, "the robot's parameters give an inertia matrix that is not
// positive definite" naming no effect, or (a rotor inertia of 1e300) exit 0 with torques of 1e301 that
// identify then refused.
TEST(CliBadInputRest, InjectedEffectsAreBoundedAndNamed) {
    const std::string out = scratch("effects.csv").string();
    for (const std::string effect : {"coulomb_offset:joint=1,value=1e300", "cogging:joint=2,amplitude=1e300,order=6",
                                     "gravity:tilt=3,direction=0,mx1=1e300", "rotor_inertia:joint=2,value=1e300"}) {
        expect_refused_on_one_line(jacobid("simulate --robot " + planar_robot() + " --duration 2 -o " + out + " --effect " + effect),
                                   {"--effect '" + effect + "' key '", "must be within +-1e+06"});
        EXPECT_FALSE(fs::exists(out)) << effect;
    }
    expect_refused_on_one_line(jacobid("simulate --robot " + planar_robot() + " --duration 2 -o " + out + " --effect rotor_inertia:joint=2,value=-1"),
                               {"--effect 'rotor_inertia:joint=2,value=-1' key 'value'", "a rotor inertia must be >= 0"});
    const std::string file = write("effects.yaml", "effects:\n  - {name: coulomb_offset, joint: 1, value: 1e300}\n");
    expect_refused_on_one_line(jacobid("simulate --robot " + planar_robot() + " --duration 2 -o " + out + " --effects " + file),
                               {file, "must be within +-1e+06"});
}

// Gravity of 1e308 (the example): before, identify said "no moving joint", a wrong cause.
TEST(CliBadInputRest, HugeGravityIsRefusedWhereItIsRead) {
    const std::string mdh = write("gravity.yaml",
                                  "model: mdh\ngravity: [1e308, 0, 0]\njoints:\n"
                                  "  - {name: j1, sigma: 0, alpha: 0, d: 0, theta: 0, r: 0}\n"
                                  "  - {name: j2, sigma: 0, alpha: 0, d: 0.5, theta: 0, r: 0}\n");
    for (const std::string& command : {"identify --print-base --robot " + mdh, "simulate --duration 1 -o " + scratch("g.csv").string() + " --robot " + mdh}) {
        expect_refused_on_one_line(jacobid(command), {"gravity.yaml:2:", "gravity", "at most 1000 m/s^2"});
    }
}

// simulate wrote headers its own reader refuses: two joints on one column, a joint on the time column or on
// a reference column it writes itself.
TEST(CliBadInputRest, SimulateRefusesColumnNamesItCouldNotReadBack) {
    const std::string out = scratch("columns.csv").string();
    const std::string base = "model: planar2r\nL1: 0.5\njoints:\n";
    const struct {
        const char* name;
        const char* joints;
        std::string expected;
    } cases[] = {
        {"twice.yaml", "  - {name: j1, position: q1, torque: tau1}\n  - {name: j2, position: q1, torque: tau2}\n", "joint 2 (j2)'s position reads column 'q1'"},
        {"time.yaml", "  - {name: j1, position: t, torque: tau1}\n  - {name: j2, position: q2, torque: tau2}\n", "joint 1 (j1)'s position reads column 't'"},
        {"reference.yaml", "  - {name: j1, position: q1, torque: q_ref1}\n  - {name: j2, position: q2, torque: tau2}\n",
         "joint 1 (j1) reads column 'q_ref1', which is the reference column simulate writes for joint 1"},
    };
    for (const auto& c : cases) {
        expect_refused_on_one_line(jacobid("simulate --duration 1 -o " + out + " --robot " + write(c.name, base + c.joints)), {c.expected});
        EXPECT_FALSE(fs::exists(out)) << c.name;
    }
}

}  // namespace
