// SPDX-License-Identifier: MIT
// Issue 20 ("Bad input, round two"): log headers and the columns a robot description maps to them.
// docs/reliability.md, "Bad input, round two: candump captures, CAN ids, log headers".
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "cli_refusal.hpp"
#include "run_command.hpp"
#include "scratch_directory.hpp"

namespace {

namespace fs = std::filesystem;
using jacobid::test::run_command;

jacobid::test::CommandResult jacobid(const std::string& args) { return run_command("timeout 60 " + std::string(JACOBID_EXECUTABLE) + " " + args); }

std::string write(const std::string& name, const std::string& text) {
    const fs::path dir = jacobid::test::scratch_directory() / "bad_headers";
    fs::create_directories(dir);
    std::ofstream(dir / name) << text;
    return (dir / name).string();
}

// A short valid log of the planar 2R, made once.
const std::string& planar_log() {
    static const std::string path = [] {
        const std::string p = write("planar.csv", "");
        const auto r = jacobid("simulate --duration 3 --quiet -o " + p);
        EXPECT_EQ(r.exit_code, 0) << r.err;
        return p;
    }();
    return path;
}

const auto read = jacobid::test::read_text;

// Refused (exit 2, one line with the key words), and nothing else on stderr.
void expect_refused_on_one_line(const jacobid::test::CommandResult& r, std::initializer_list<std::string> words) {
    jacobid::test::expect_refused(r, words);
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "not one line: " << r.err;
}

std::string robot_with_joints(const std::string& name, const std::string& j1, const std::string& j2) {
    return write(name, "model: planar2r\nL1: 0.5\njoints:\n  - {name: j1, " + j1 + ", limits: [-2.5, 2.5]}\n  - {name: j2, " + j2 +
                           ", limits: [-2.5, 2.5]}\n");
}

// The planar 2R on the log's own columns.
std::string planar_robot() { return robot_with_joints("planar.yaml", "position: q1, torque: tau1", "position: q2, torque: tau2"); }

TEST(CliBadHeaders, Utf8ByteOrderMarkIsNotPartOfTheFirstName) {
    const std::string bom = write("bom.csv", "\xEF\xBB\xBF" + read(planar_log()));
    const auto r = jacobid("identify --quiet --robot " + planar_robot() + " --in " + bom);
    EXPECT_EQ(r.exit_code, 0) << r.err;  // before: "no column 't'" for the column named BOM + 't'
}

TEST(CliBadHeaders, DuplicateColumnNamesNameBothColumns) {
    std::string text = read(planar_log());
    text.replace(text.find("q2"), 2, "q1");
    expect_refused_on_one_line(jacobid("identify --robot " + planar_robot() + " --in " + write("dup.csv", text)), {"duplicate column name 'q1' (columns 2 and 3)"});
}

TEST(CliBadHeaders, JointOnTheTimeColumnIsRefused) {
    const std::string robot = robot_with_joints("time_robot.yaml", "position: t, torque: tau1", "position: q2, torque: tau2");
    expect_refused_on_one_line(jacobid("identify --robot " + robot + " --in " + planar_log()),
                   {"joint 1 (j1)'s position reads column 't', which is also the time column"});
}

TEST(CliBadHeaders, TwoJointsOnOneColumnAreRefused) {
    const std::string robot = robot_with_joints("same_column.yaml", "position: q1, torque: tau1", "position: q2, torque: tau1");
    expect_refused_on_one_line(jacobid("diagnose --robot " + robot + " --in " + planar_log()),
                   {"joint 2 (j2)'s torque reads column 'tau1', which is also joint 1 (j1)'s torque"});
}

TEST(CliBadHeaders, LogFormatReadingTheTimeAsAPositionIsRefused) {
    const std::string format = write("time_format.yaml", "header: true\ntime: {column: t}\npositions: [t, q2]\ntorques: [tau1, tau2]\n");
    expect_refused_on_one_line(jacobid("identify --robot " + planar_robot() + " --log-format " + format + " --in " + planar_log()),
                   {"'positions[0]' reads raw column 1, which 'time' also reads"});
}

// 400 000 column names were checked for duplicates pairwise (8e10 comparisons: minutes). The work is bounded,
// not timed: a million columns (5e11 pairs) under a CPU-time limit of 30 s (`ulimit -t`, the process is
// killed beyond it), which a pairwise check cannot meet on any machine and the name index meets many times
// over, under the sanitizers too; CPU time, not wall time, so other load on the machine does not count.
// The time itself is measured by benchmarks/bench_csv_header.cpp.
TEST(CliBadHeaders, WideHeaderIsReadInLinearTime) {
    constexpr int kColumns = 1000000;
    std::string header = "t,q1,q2,tau1,tau2", row = "0,0,0,0,0";
    for (int c = 0; c < kColumns; ++c) {
        header += ",x" + std::to_string(c);
        row += ",0";
    }
    const std::string wide = write("wide.csv", header + "\n" + row + "\n" + row + "\n");
    const auto r = run_command("ulimit -t 30; timeout 600 " + std::string(JACOBID_EXECUTABLE) + " identify --robot " + planar_robot() + " --in " + wide);
    EXPECT_EQ(r.exit_code, 2) << r.err;  // two identical time stamps: refused, after the header was read (killed: 152)
    EXPECT_NE(r.err.find("time"), std::string::npos) << r.err;
}

}  // namespace
