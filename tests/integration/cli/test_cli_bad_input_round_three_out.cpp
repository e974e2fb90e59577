// SPDX-License-Identifier: MIT
// Issue 36 ("Bad input, round three"), outputs and command options on the host: an output is never written
// over an input (compared as files: links too), nothing wrong or degenerate comes out with exit 0 (drive gains
// from one log twice, an excitation designed for a 1e-10 rad motion, a simulated reference that is not a
// motion of the robot), URDF limits are checked, and each refusal names what is wrong. Each case is one line
// with exit status 2; docs/reliability.md, "Round three (issue 36)", "Outputs and command options".
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "cli_refusal.hpp"
#include "run_command.hpp"
#include "scratch_directory.hpp"

namespace {

namespace fs = std::filesystem;
using jacobid::test::expect_refused;
using jacobid::test::read_text;
using jacobid::test::run_command;

const std::string kSource = JACOBID_TESTS_DIR;

jacobid::test::CommandResult jacobid(const std::string& args) { return run_command("timeout 120 " + std::string(JACOBID_EXECUTABLE) + " " + args); }

fs::path scratch(const std::string& name) { return jacobid::test::scratch_file("round_three_out", name); }

std::string write(const std::string& name, const std::string& text) { return jacobid::test::write_scratch_file("round_three_out", name, text); }

bool excite_built() { return jacobid("excite --help").exit_code == 0; }

// The test arm (tests/data/export_arm.urdf) copied beside its description, with a symbolic and a hard link
// to the URDF: what an output must never be written through.
struct UrdfRobot {
    std::string yaml, urdf, symlink, hardlink, text;
};

const UrdfRobot& urdf_robot() {
    static const UrdfRobot robot = [] {
        UrdfRobot r;
        r.urdf = scratch("arm.urdf").string();
        fs::copy_file(kSource + "/data/export_arm.urdf", r.urdf, fs::copy_options::overwrite_existing);
        r.text = read_text(r.urdf);
        r.yaml = write("arm.yaml", "model: urdf\nurdf: arm.urdf\n");
        r.symlink = scratch("symlink.urdf").string();
        r.hardlink = scratch("hardlink.urdf").string();
        fs::create_symlink(r.urdf, r.symlink);
        fs::create_hard_link(r.urdf, r.hardlink);
        return r;
    }();
    return robot;
}

// Whatever a command was asked, the URDF it read is unchanged.
void expect_urdf_kept() { EXPECT_EQ(read_text(urdf_robot().urdf), urdf_robot().text); }

// --- 1. Inputs overwritten -----------------------------------------------------------------------------------

TEST(CliOutputGuard, AnExportThroughALinkToTheRobotsOwnUrdfIsRefusedAndTheUrdfKept) {
    const UrdfRobot& r = urdf_robot();
    const std::string log = write("any.csv", "t,q1\n0,0\n");
    for (const std::string& link : {r.symlink, r.hardlink}) {
        expect_refused(jacobid("identify --robot " + r.yaml + " --in " + log + " --export-urdf " + link),
                       {"--export-urdf " + link + " (the file " + r.urdf + "): is the input given to the urdf: of --robot " + r.yaml});
        expect_urdf_kept();
    }
}

TEST(CliOutputGuard, AnExportOntoTheInLogThroughAHardLinkIsRefused) {
    const UrdfRobot& r = urdf_robot();
    const std::string log = write("kept.csv", "t,q1\n0,0\n");
    const std::string link = scratch("kept-link.csv").string();
    fs::create_hard_link(log, link);
    expect_refused(jacobid("identify --robot " + r.yaml + " --in " + log + " --export-robot " + link),
                   {"--export-robot " + link + " (the file " + log + "): is the input given to --in"});
    EXPECT_EQ(read_text(log), "t,q1\n0,0\n");
}

// Every command that reads a robot description compares its outputs with the URDF the description names.
TEST(CliOutputGuard, EveryCommandComparesItsOutputsWithTheRobotsUrdf) {
    const UrdfRobot& r = urdf_robot();
    const std::string log = write("any2.csv", "t,q1\n0,0\n");
    const std::string robot = " --robot " + r.yaml + " ";
    const std::string urdf_input = "is the input given to the urdf: of --robot";
    expect_refused(jacobid("simulate" + robot + "-o " + r.symlink), {"--out " + r.symlink, urdf_input});
    expect_refused(jacobid("simulate" + robot + "-o " + scratch("s.csv").string() + " --states " + r.hardlink), {"--states " + r.hardlink, urdf_input});
    expect_refused(jacobid("identify" + robot + "--in " + log + " -o " + r.symlink), {"--output " + r.symlink, urdf_input});
    expect_refused(jacobid("diagnose" + robot + "--in " + log + " -o " + r.symlink), {"--output " + r.symlink, urdf_input});
    expect_refused(jacobid("montecarlo" + robot + "--runs 2 -o " + r.hardlink), {"--output " + r.hardlink, urdf_input});
    expect_refused(jacobid("sim-can" + robot + "--duration 1 --candump " + r.symlink), {"--candump " + r.symlink, urdf_input});
    if (excite_built()) {
        expect_refused(jacobid("excite" + robot + "-o " + r.symlink), {"--output " + r.symlink, urdf_input});
        expect_refused(jacobid("excite" + robot + "-o " + scratch("e.csv").string() + " --json " + r.hardlink), {"--json " + r.hardlink, urdf_input});
    }
    expect_urdf_kept();
}

TEST(CliOutputGuard, TwoOutputsNamingOneFileThroughALinkAreRefused) {
    const std::string out = write("out.csv", "");
    const std::string link = scratch("out-link.csv").string();
    fs::create_symlink(out, link);
    expect_refused(jacobid("simulate --duration 1 -o " + out + " --states " + link),
                   {"--states " + link + " (the file " + out + "): is also the output of --out; give two different files"});
    const std::string log = write("in.csv", "t,q1\n0,0\n");
    expect_refused(jacobid("identify --robot " + urdf_robot().yaml + " --in " + log + " -o " + out + " --export-robot " + link),
                   {"--export-robot " + link, "is also the output of --output"});
}

// --report DIR writes report.md and PNG plots in DIR: none may be a file the command reads or writes.
TEST(CliOutputGuard, AReportFolderHoldingAnInputOrOutputOfTheReportsNamesIsRefused) {
    const fs::path dir = scratch("report-dir");
    fs::create_directories(dir);
    const std::string robot = (dir / "report.md").string();
    fs::copy_file(kSource + "/../examples/robots/planar2r.yaml", robot, fs::copy_options::overwrite_existing);
    const std::string text = read_text(robot);
    expect_refused(jacobid("montecarlo --runs 2 --robot " + robot + " --report " + dir.string()),
                   {"--report " + dir.string() + ": the report writes report.md and PNG plots in it, and " + robot + " is the file given to --robot"});
    const std::string log = write("in-report.csv", "t,q1\n0,0\n");
    expect_refused(jacobid("identify --robot " + urdf_robot().yaml + " --in " + log + " -o " + (dir / "torque_jacobi.png").string() + " --report " + dir.string()),
                   {"is the file given to --output"});
    EXPECT_EQ(read_text(robot), text);
}

// record --on-gap split writes OUT's stem.N.ext segments: a summary named like one would collide.
TEST(CliOutputGuard, ARecordSummaryNamedLikeASplitSegmentIsRefused) {
    const std::string out = scratch("rec.csv").string(), summary = scratch("rec.2.csv").string();
    expect_refused(jacobid("record --udp 127.0.0.1:0 --on-gap split -o " + out + " --summary " + summary),
                   {"--summary " + summary + ": --on-gap split may write this file as a segment of --out " + out + " (rec.N.csv)"});
}

TEST(CliOutputGuard, DriveGainsOutputOntoTheLoadedLogIsRefused) {
    const std::string unloaded = write("unloaded.csv", "t,q1\n0,0\n");
    const std::string loaded = write("loaded.csv", "t,q1\n0,1\n");
    expect_refused(jacobid("identify --robot " + urdf_robot().yaml + " --drive-gains --payload-mass 1 --in " + unloaded + " --loaded " + loaded + " -o " + loaded),
                   {"--output " + loaded + ": is the input given to --loaded"});
    EXPECT_EQ(read_text(loaded), "t,q1\n0,1\n");
}

// Found by the audit (5): an empty path was "not given" (--robot '' simulated the default robot, exit 0; -o ''
// said ": cannot open for writing"), and '-' where an option has no standard output was a file named '-'.
TEST(CliPathOptions, AnEmptyPathOrADashWhereNoStandardStreamIsMeantIsRefusedNamingTheOption) {
    expect_refused(jacobid("simulate --duration 1 --robot '' -o " + scratch("e.csv").string()), {"--robot: expected a file path, got ''"});
    expect_refused(jacobid("simulate --duration 1 -o ''"), {"--out: expected a file path, got ''"});
    const auto dash = jacobid("simulate --duration 1 -o -");
    expect_refused(dash, {"--out: expected a file path, got '-' (this option does not read or write standard input/output)"});
    EXPECT_FALSE(fs::exists("-"));
    expect_refused(jacobid("identify --robot r.yaml --in x.csv --report ''"), {"--report: expected a file path, got ''"});
    expect_refused(jacobid("identify --robot r.yaml --in ''"), {"--in: expected a file path, got ''"});
    expect_refused(jacobid("record --udp 127.0.0.1:0 -o ''"), {"--out: expected a file path, got ''"});
    expect_refused(jacobid("differentiate --in '' -c q1"), {"--in: expected a file path, got ''"});
    // Where '-' is standard output it stays accepted.
    const auto to_stdout = jacobid("kernel --order 1 --ts 0.001 --window 0.02 -o -");
    EXPECT_EQ(to_stdout.exit_code, 0) << to_stdout.err;
}

// --- 2. Wrong numbers with exit 0 ------------------------------------------------------------------------------

const std::string kUr5 = kSource + "/../examples/robots/ur5_like.yaml";

// A short simulated log of the UR5-like arm, made once.
const std::string& ur5_log() {
    static const std::string path = [] {
        const std::string p = scratch("ur5.csv").string();
        const auto r = jacobid("simulate --quiet --robot " + kUr5 + " --duration 10 --seed 3 --torque-noise 0.3 -o " + p);
        EXPECT_EQ(r.exit_code, 0) << r.err;
        return p;
    }();
    return path;
}

std::string drive_gains(const std::string& in, const std::string& loaded, const std::string& more = " --payload-mass 2") {
    return "identify --quiet --robot " + kUr5 + " --drive-gains --in " + in + " --loaded " + loaded + more;
}

// Before: gains of ~1e-13 with a std of 3.4, TLS nan and a `gains:` line, exit 0.
TEST(CliDriveGains, OneLogAsBothRunsIsRefusedByFileAndByContent) {
    const std::string link = scratch("ur5-link.csv").string(), copy = scratch("ur5-copy.csv").string();
    fs::create_symlink(ur5_log(), link);
    fs::copy_file(ur5_log(), copy);
    for (const std::string& loaded : {ur5_log(), link}) {
        const auto r = jacobid(drive_gains(ur5_log(), loaded));
        expect_refused(r, {"--loaded " + loaded + ": is the file given to --in (" + ur5_log() + ")", "give the run with the payload"});
        EXPECT_EQ(r.out.find("gains: ["), std::string::npos) << r.out;
    }
    const auto r = jacobid(drive_gains(ur5_log(), copy));
    expect_refused(r, {"--loaded " + copy + ": holds exactly the positions and efforts of --in " + ur5_log()});
    EXPECT_EQ(r.out.find("gains: ["), std::string::npos) << r.out;
}

// A loaded run that differs from the unloaded one by one cell (no payload torque) is not a fit to print.
TEST(CliDriveGains, AGainTheLogsDoNotDetermineIsRefusedNotPrinted) {
    std::ifstream in(ur5_log());
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::size_t cell_end = text.find('\n') + 1;  // the first data row's tau1 (column 8): one more digit
    for (int c = 0; c < 8; ++c) cell_end = text.find(',', cell_end) + 1;
    text.insert(cell_end - 1, "1");
    const std::string nearly = write("ur5-nearly.csv", text);
    const auto r = jacobid(drive_gains(ur5_log(), nearly));
    expect_refused(r, {"--drive-gains: the gain of joint 1 (", "do not determine it (a gain must be positive and known to better than 100 %)"});
    EXPECT_EQ(r.out.find("gains: ["), std::string::npos) << r.out;
}

// Before: "--payload-mass 0: expected the payload's mass in kg, > 0" for an option never given.
TEST(CliDriveGains, AMissingPayloadMassIsNamedAsMissing) {
    expect_refused(jacobid(drive_gains(ur5_log(), ur5_log(), "")), {"--drive-gains needs --payload-mass KG"});
}

// A reference for the planar 2R: one period of q = a sin(w t) on both joints (q2 = -q1), `rows` rows of `step`
// s, the velocity and acceleration columns multiplied by `qd_factor` and `qdd_factor` (1: consistent), and
// a third joint's columns when `third_joint`.
std::string sine_table(const std::string& name, double step, int rows, double amplitude, double qd_factor = 1.0, double qdd_factor = 1.0,
                       bool third_joint = false) {
    std::string text = std::string("t,q1,q2,qd1,qd2,qdd1,qdd2") + (third_joint ? ",q3,qd3,qdd3" : "") + "\n";
    const double w = 2.0 * M_PI / (step * (rows - 1));
    for (int i = 0; i < rows; ++i) {
        const double t = step * i, q = amplitude * std::sin(w * t), qd = amplitude * w * std::cos(w * t) * qd_factor,
                     qdd = -amplitude * w * w * std::sin(w * t) * qdd_factor;
        char row[400];
        std::snprintf(row, sizeof row, "%.9g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g%s\n", t, q, -q, qd, -qd, qdd, -qdd, third_joint ? ",0,0,0" : "");
        text += row;
    }
    return write(name, text);
}

const std::string kLimitedPlanar = "model: planar2r\nL1: 0.5\njoints:\n  - {name: j1, position: q1, torque: tau1, limits: [-2.5, 2.5]}\n"
                                   "  - {name: j2, position: q2, torque: tau2, limits: [-2.5, 2.5]}\n";

jacobid::test::CommandResult simulate_table(const std::string& table) {
    return jacobid("simulate --quiet --robot " + write("limited.yaml", kLimitedPlanar) + " --trajectory " + table + " -o " + scratch("traj-log.csv").string());
}

TEST(CliSimulateTrajectory, AConsistentTableWithinTheLimitsIsFollowed) {
    const auto r = simulate_table(sine_table("fine.csv", 0.01, 201, 1.0));
    EXPECT_EQ(r.exit_code, 0) << r.err;
}

// Before: a 2-row table of 1 ns steps gave a log of one row, exit 0.
TEST(CliSimulateTrajectory, AStepOutsideTheStatedRangeOrALogOfOneSampleIsRefused) {
    const std::string ns = write("ns.csv", "t,q1,q2,qd1,qd2,qdd1,qdd2\n0,0,0,0,0,0,0\n1e-9,0,0,0,0,0,0\n");
    expect_refused(simulate_table(ns), {ns + ": line 3, column t: time step 1e-09 s, expected 1e-06 .. 1000 s (is t in seconds?)"});
    const std::string short_table = write("short.csv", "t,q1,q2,qd1,qd2,qdd1,qdd2\n0,0,0,0,0,0,0\n1e-5,0,0,0,0,0,0\n");
    expect_refused(simulate_table(short_table), {"--trajectory " + short_table + " lasts 1e-05 s (its last t) and at --rate 1000 Hz gives a log of one sample"});
    expect_refused(jacobid("simulate --duration 1e-4 -o " + scratch("one.csv").string()), {"--duration 0.0001 s at --rate 1000 Hz gives a log of one sample"});
}

// Before: exit 0, the interpolated reference oscillating between the rows.
TEST(CliSimulateTrajectory, DerivativeColumnsThatAreNotTheDerivativesAreRefusedWithTheirLine) {
    const std::string zero_qd = sine_table("zero-qd.csv", 0.01, 201, 1.0, 0.0, 0.0);
    expect_refused(simulate_table(zero_qd), {zero_qd + ": line 3, columns q1, qd1, qdd1: q1 moves by", "qd1 and qdd1 must be q1's derivatives"});
    const std::string degrees = sine_table("degrees.csv", 0.01, 201, 1.0, 180.0 / M_PI, 180.0 / M_PI);
    expect_refused(simulate_table(degrees), {degrees + ": line 3, columns q1, qd1, qdd1"});
    const std::string zero_qdd = sine_table("zero-qdd.csv", 0.01, 201, 1.0, 1.0, 0.0);
    expect_refused(simulate_table(zero_qdd), {zero_qdd + ": line 3, columns qd1, qdd1: qd1 changes by", "qdd1 must be qd1's derivative"});
}

// Before: exit 0, the robot commanded 3 rad where its description allows 2.5.
TEST(CliSimulateTrajectory, AReferenceBeyondTheJointLimitsIsRefused) {
    const std::string far = sine_table("far.csv", 0.01, 201, 3.0);
    expect_refused(simulate_table(far), {far + ": line ", ", column q1: position ", "is outside joint 1 (j1)'s limits [-2.5, 2.5] of the robot description"});
}

// Before: a table with a third joint's columns was followed by the 2R, the columns dropped, exit 0.
TEST(CliSimulateTrajectory, ATableForAnotherRobotIsRefusedNamingTheColumn) {
    const std::string three = sine_table("three.csv", 0.01, 201, 1.0, 1.0, 1.0, true);
    expect_refused(simulate_table(three), {three + ":1: column 8 'q3' is not read by the simulator (the robot has 2 joints: expected the columns t, "
                                                   "q1..q2, qd1..qd2, qdd1..qdd2; a table for another robot?)"});
    const std::string one = write("one-joint.csv", "t,q1,qd1,qdd1\n0,0,0,0\n0.01,0,0,0\n");
    expect_refused(simulate_table(one), {one + ":1: no column 'q2' (the robot has 2 joints"});
}

// Found by the audit (5): --velocity-limit 1e-308 logged a robot standing still, exit 0 (identify then refused
// the log as "standing still", blaming the log).
TEST(CliSimulateMoves, LimitsThatAllowNoMeasurableMotionAreRefused) {
    expect_refused(jacobid("simulate --duration 10 --velocity-limit 1e-4 -o " + scratch("v.csv").string()),
                   {"--velocity-limit 0.0001 rad/s: a move within --duration 10 s reaches at most v T / 1.875 = 0.000533 rad, less than the 0.001 rad"});
    expect_refused(jacobid("simulate --duration 10 --acceleration-limit 1e-308 -o " + scratch("a.csv").string()),
                   {"--acceleration-limit 1e-308 rad/s^2: a move within --duration 10 s reaches at most a T^2 / 5.77"});
    expect_refused(jacobid("montecarlo --runs 2 --velocity-limit 1e-308 -o " + scratch("m.json").string()), {"--velocity-limit 1e-308 rad/s"});
    const auto slow = jacobid("simulate --quiet --duration 2 --velocity-limit 0.01 -o " + scratch("slow.csv").string());
    EXPECT_EQ(slow.exit_code, 0) << slow.err;
}

// --- 3. URDF limits ----------------------------------------------------------------------------------------

// Before: joint 2's <limit lower="1" upper="1"> became [-pi, pi] and excite designed a motion over it.
TEST(CliUrdfLimits, ARevoluteJointWithoutARangeIsRefusedByEveryCommand) {
    std::string urdf = read_text(kSource + "/data/export_arm.urdf");
    const std::size_t joint = urdf.find("type=\"revolute\"", urdf.find("type=\"revolute\"") + 1);  // the second revolute joint
    const std::size_t lower = urdf.find("lower=", joint), upper_end = urdf.find('"', urdf.find("upper=\"", joint) + 7);
    ASSERT_LT(lower, upper_end);
    urdf.replace(lower, upper_end + 1 - lower, "lower=\"1\" upper=\"1\"");
    const std::string file = write("flat.urdf", urdf);
    const std::string robot = write("flat.yaml", "model: urdf\nurdf: flat.urdf\n");
    const std::string why = "<limit lower='1' upper='1'>: a revolute joint needs <limit lower upper> with lower < upper (rad)";
    expect_refused(jacobid("simulate --robot " + robot + " -o " + scratch("flat.csv").string()), {file + ": element <joint name='shoulder_lift'>: " + why});
    expect_refused(jacobid("identify --print-base --robot " + robot), {file, why});
    if (excite_built()) expect_refused(jacobid("excite --robot " + robot + " -o " + scratch("flat-excite.csv").string()), {file, why});
}

// --- 4. Messages that blame the right thing -----------------------------------------------------------------

// Before: 'dir/package:/arm_description/urdf/arm.urdf' is not a readable file.
TEST(CliUrdfMessages, APackageUriIsResolvedTheRosWayOrSaysHowToFixIt) {
    const std::string yaml = write("pkg.yaml", "model: urdf\nurdf: package://arm_description/urdf/arm.urdf\n");
    const std::string unset = "env -u ROS_PACKAGE_PATH -u AMENT_PREFIX_PATH ";
    expect_refused(run_command(unset + JACOBID_EXECUTABLE + " identify --print-base --robot " + yaml),
                   {yaml + ":2:7: urdf: 'package://arm_description/urdf/arm.urdf': no ROS package 'arm_description' holding 'urdf/arm.urdf' "
                           "(ROS_PACKAGE_PATH unset, AMENT_PREFIX_PATH unset",
                    "give the URDF's path (relative to this file or absolute)"});
    const fs::path package = scratch("ws") / "src" / "arm_description";
    fs::create_directories(package / "urdf");
    std::ofstream(package / "package.xml") << "<package><name>arm_description</name></package>\n";
    fs::copy_file(kSource + "/data/export_arm.urdf", package / "urdf" / "arm.urdf", fs::copy_options::overwrite_existing);
    const auto ros1 = run_command(unset + "ROS_PACKAGE_PATH=" + (scratch("ws") / "src").string() + " " + JACOBID_EXECUTABLE +
                                  " identify --print-base --robot " + yaml);
    EXPECT_EQ(ros1.exit_code, 0) << ros1.err;
    EXPECT_NE(ros1.out.find("model urdf (" + yaml + "): 4 joints"), std::string::npos) << ros1.out;
    const fs::path prefix = scratch("install");
    fs::create_directories(prefix / "share");
    fs::copy(package, prefix / "share" / "arm_description", fs::copy_options::recursive | fs::copy_options::overwrite_existing);
    const auto ros2 = run_command(unset + "AMENT_PREFIX_PATH=/nonexistent:" + prefix.string() + " " + JACOBID_EXECUTABLE + " identify --print-base --robot " + yaml);
    EXPECT_EQ(ros2.exit_code, 0) << ros2.err;
}

// Before: "invalid URDF (urdfdom rejected it: malformed XML, a missing <robot>, ...)" and urdfdom's own
// "Error:" line printed apart.
TEST(CliUrdfMessages, UrdfdomsOwnReasonIsTheMessage) {
    std::string urdf = read_text(kSource + "/data/export_arm.urdf");
    const std::size_t child = urdf.find("<child link=\"", urdf.find("name=\"shoulder_lift\""));
    urdf.insert(urdf.find('"', child + 13), "_missing");
    const std::string file = write("missing-child.urdf", urdf);
    const auto r = jacobid("identify --print-base --robot " + write("missing-child.yaml", "model: urdf\nurdf: missing-child.urdf\n"));
    expect_refused(r, {file + ": invalid URDF: Failed to build tree: child link [", "_missing] of joint [shoulder_lift] not found (urdfdom)"});
    EXPECT_EQ(r.err.find("Error:"), std::string::npos) << r.err;
}

}  // namespace
