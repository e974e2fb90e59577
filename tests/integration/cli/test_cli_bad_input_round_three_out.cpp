// SPDX-License-Identifier: MIT
// Issue 36 ("Bad input, round three"), outputs and command options on the host: an output is never written
// over an input (compared as files: links too), nothing wrong or degenerate comes out with exit 0 (drive gains
// from one log twice, an excitation designed for a 1e-10 rad motion, a simulated reference that is not a
// motion of the robot), URDF limits are checked, and each refusal names what is wrong. Each case is one line
// with exit status 2; docs/reliability.md, "Round three (issue 36)", "Outputs and command options".
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
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

TEST(CliOutputGuard, DriveGainsOutputOntoTheLoadedLogIsRefused) {
    const std::string unloaded = write("unloaded.csv", "t,q1\n0,0\n");
    const std::string loaded = write("loaded.csv", "t,q1\n0,1\n");
    expect_refused(jacobid("identify --robot " + urdf_robot().yaml + " --drive-gains --payload-mass 1 --in " + unloaded + " --loaded " + loaded + " -o " + loaded),
                   {"--output " + loaded + ": is the input given to --loaded"});
    EXPECT_EQ(read_text(loaded), "t,q1\n0,1\n");
}

}  // namespace
