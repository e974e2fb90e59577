// SPDX-License-Identifier: MIT
// Issue 36 ("Bad input, round three"), reading logs through the commands: one log given twice (a copy, a
// symlink, a hard link), efforts all null or all 0, a time column in ms, --max-gap over a hole, a header in
// another delimiter, bare-CR line ends. docs/reliability.md, "Round three (issue 36)", "Reading logs".
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
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

jacobid::test::CommandResult jacobid(const std::string& args) { return run_command("timeout 120 " + std::string(JACOBID_EXECUTABLE) + " " + args); }

fs::path dir() {
    const fs::path d = jacobid::test::scratch_directory() / "bad_logs_round_three";
    fs::create_directories(d);
    return d;
}

std::string write(const std::string& name, const std::string& text) {
    std::ofstream(dir() / name, std::ios::binary) << text;
    return (dir() / name).string();
}

std::string planar_robot() {
    return write("planar.yaml", "model: planar2r\nL1: 0.5\njoints:\n  - {name: j1, position: q1, torque: tau1, limits: [-2.5, 2.5]}\n"
                                "  - {name: j2, position: q2, torque: tau2, limits: [-2.5, 2.5]}\n");
}

// A valid planar 2R log (t, q1, q2, tau1, tau2, ...), made once.
const std::string& planar_log() {
    static const std::string path = [] {
        const std::string p = (dir() / "planar.csv").string();
        const auto r = jacobid("simulate --duration 4 --quiet -o " + p);
        EXPECT_EQ(r.exit_code, 0) << r.err;
        return p;
    }();
    return path;
}

std::vector<std::string> lines_of(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    return lines;
}

// The planar log with each data row changed by `edit` (its cells split at ','), the header kept.
template <typename Edit>
std::string edited_log(const std::string& name, Edit edit) {
    const std::vector<std::string> lines = lines_of(jacobid::test::read_text(planar_log()));
    std::string out = lines.front() + "\n";
    for (std::size_t i = 1; i < lines.size(); ++i) {
        std::vector<std::string> cells;
        std::istringstream row(lines[i]);
        for (std::string c; std::getline(row, c, ',');) cells.push_back(c);
        edit(cells);
        for (std::size_t c = 0; c < cells.size(); ++c) out += (c ? "," : "") + cells[c];
        out += "\n";
    }
    return write(name, out);
}

TEST(CliBadLogsRoundThree, OneLogGivenTwiceIsRefusedNamingBothPaths) {
    const std::string a = planar_log();
    const std::string copy = write("copy_of_planar.csv", jacobid::test::read_text(a));
    const fs::path link = dir() / "link_to_planar.csv", hard = dir() / "hard_planar.csv";
    fs::remove(link);
    fs::remove(hard);
    fs::create_symlink(a, link);
    fs::create_hard_link(a, hard);
    const std::string robot = planar_robot();
    // A byte-identical copy under another name was counted twice: std too small by sqrt(2), exit 0.
    expect_refused(jacobid("identify --robot " + robot + " --in " + a + " --in " + copy),
                   {"--in " + copy + ": given twice (--in number 1 and 2), as " + copy + " is a byte-identical copy of " + a + ";"});
    expect_refused(jacobid("identify --robot " + robot + " --in " + a + " --in " + link.string()),
                   {"--in " + link.string() + ": given twice (--in number 1 and 2), as " + a + " and " + link.string() + " are one file"});
    expect_refused(jacobid("identify --robot " + robot + " --in " + hard.string() + " --in " + a), {"are one file"});
    // diagnose takes several logs through the same check.
    expect_refused(jacobid("diagnose --robot " + robot + " --in " + a + " --in " + copy), {"is a byte-identical copy of " + a});
    // --validate on the --in log (or its copy) validates nothing: a warning naming both.
    const auto in_sample = jacobid("identify --robot " + robot + " --in " + a + " --validate " + copy);
    EXPECT_EQ(in_sample.exit_code, 0) << in_sample.err;
    EXPECT_NE(in_sample.err.find("jacobid identify: warning: --validate " + copy + " is the --in log (" + copy + " is a byte-identical copy of " + a +
                                 "): its validation figures are in-sample"),
              std::string::npos)
        << in_sample.err;
    // Two different logs stay accepted (the check does not refuse by size alone).
    const std::string other = edited_log("other.csv", [](std::vector<std::string>& c) { c[3] = c[3] + "1"; });
    const auto ok = jacobid("identify --quiet --robot " + robot + " --in " + a + " --in " + other);
    EXPECT_EQ(ok.exit_code, 0) << ok.err;
}

TEST(CliBadLogsRoundThree, EffortsAllNullOrAllZeroAreRefused) {
    const std::string robot = planar_robot();
    // Every torque 0 in every row: every parameter came out exactly 0 with std 0, exit 0.
    const std::string zeros = edited_log("zero_torques.csv", [](std::vector<std::string>& c) { c[3] = c[4] = "0"; });
    expect_refused(jacobid("identify --robot " + robot + " --in " + zeros),
                   {zeros + ": every torque column ('tau1', 'tau2') is 0 in every one of its", "no joint's effort was logged"});
    // A log format whose efforts are all null.
    const std::string format = write("null_efforts.yaml", "time: {column: t}\npositions: [q1, q2]\ntorques: [null, null]\n");
    expect_refused(jacobid("identify --robot " + robot + " --log-format " + format + " --in " + planar_log()),
                   {format + ":3:10: torques: every joint is null (no actuator)"});
}

TEST(CliBadLogsRoundThree, TimeInMillisecondsIsRefusedWithTheLikelyUnit) {
    const std::string ms = edited_log("ms.csv", [](std::vector<std::string>& c) { c[0] = std::to_string(1000.0 * std::stod(c[0])); });
    expect_refused(jacobid("identify --robot " + planar_robot() + " --in " + ms),
                   {ms + ": column 't': the median time step is 1 s, outside the plausible sample periods 10 us .. 100 ms per sample",
                    "is the time column in ms (1 ms per sample: time.scale 0.001)?"});
    // A log format with time.scale reads it.
    const std::string format = write("ms.yaml", "time: {column: t, scale: 0.001}\npositions: [q1, q2]\ntorques: [tau1, tau2]\n");
    const auto ok = jacobid("identify --quiet --robot " + planar_robot() + " --log-format " + format + " --in " + ms);
    EXPECT_EQ(ok.exit_code, 0) << ok.err;
}

TEST(CliBadLogsRoundThree, MaxGapLongerThanTenMedianStepsIsRefused) {
    // A 10 s hole: the rows from 1 s to 3 s taken out, then --max-gap 1e6 made it one step.
    const std::vector<std::string> lines = lines_of(jacobid::test::read_text(planar_log()));
    std::string text = lines.front() + "\n";
    for (std::size_t i = 1; i < lines.size(); ++i) {
        const double t = std::stod(lines[i].substr(0, lines[i].find(',')));
        if (t < 1.0 || t > 3.0) text += lines[i] + "\n";
    }
    const std::string holed = write("holed.csv", text);
    const std::string format = write("plain.yaml", "time: {column: t}\npositions: [q1, q2]\ntorques: [tau1, tau2]\n");
    expect_refused(jacobid("identify --robot " + planar_robot() + " --log-format " + format + " --max-gap 1e6 --in " + holed),
                   {holed + ": --max-gap 1e+06 s is 1e+09 median steps of 1 ms, more than the 10 median steps (10 ms) a single step may span"});
}

TEST(CliBadLogsRoundThree, HeaderInAnotherDelimiterAndBareCarriageReturnsAreNamed) {
    std::string semicolons = jacobid::test::read_text(planar_log());
    for (char& c : semicolons) c = c == ',' ? ';' : c;
    const std::string semi = write("semicolons.csv", semicolons);
    expect_refused(jacobid("identify --robot " + planar_robot() + " --in " + semi), {semi + ":1: the header '", "is one column: is the delimiter ';'?"});
    std::string cr = jacobid::test::read_text(planar_log());
    for (char& c : cr) c = c == '\n' ? '\r' : c;
    const std::string old_mac = write("cr.csv", cr);
    expect_refused(jacobid("identify --robot " + planar_robot() + " --in " + old_mac), {old_mac + ":1: the line ends are bare carriage returns"});
    // A gzip-compressed log and a header of other names were "internal error: ... told to keep none of its 1
    // columns", exit 3.
    const auto gz = run_command("gzip -c " + planar_log() + " > " + (dir() / "planar.csv.gz").string());
    ASSERT_EQ(gz.exit_code, 0) << gz.err;
    expect_refused(jacobid("identify --robot " + planar_robot() + " --in " + (dir() / "planar.csv.gz").string()),
                   {"planar.csv.gz:1: the file is compressed (gzip, zip, xz or bzip2): unpack it and give the CSV"});
    const std::string foreign = write("foreign.csv", "a,b,c\n1,2,3\n2,3,4\n");
    expect_refused(jacobid("identify --robot " + planar_robot() + " --in " + foreign), {foreign + ":1: none of the header's columns (a,b,c) is one this command reads"});
}

}  // namespace
