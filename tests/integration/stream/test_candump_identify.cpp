// SPDX-License-Identifier: MIT
// Off-line identification from a CAN capture: `jacobid sim-can --candump` writes what candump -L would
// have recorded (checked frame by frame with python-can's reader), `jacobid identify --can-config` decodes
// it with the firmware's joint profiles and must meet the identification bars against the simulation's
// truth; lost and corrupt frames are errors naming the line.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "identification_bars.hpp"
#include "run_command.hpp"
#include "scratch_directory.hpp"

namespace {

using jacobid::test::run_command;

std::string path(const std::string& name) { return (jacobid::test::scratch_directory() / name).string(); }
std::string jacobid(const std::string& args) { return std::string(JACOBID_EXECUTABLE) + " " + args; }

// MIT drivers, 4:1 gears: the shoulder's effort range covers its ~115 N.m, the elbow's its ~6 N.m.
const char* kFirmwareConfig =
    "can: {interface: can0}\n"
    "joints:\n"
    "  - {name: shoulder, profile: mit, motor_id: 1, gear_ratio: 4, velocity_range: [-65, 65], effort_range: [-30, 30]}\n"
    "  - {name: elbow, profile: mit, motor_id: 2, gear_ratio: 4, velocity_range: [-65, 65], effort_range: [-2, 2]}\n"
    "stream: {host: 127.0.0.1, port: 5005}\n";
const char* kRobot = "model: planar2r\nL1: 0.5\nfriction: {coulomb: smooth, alpha: 100}\n";

std::vector<std::string> lines_of(const std::string& file) {
    std::ifstream in(file);
    std::vector<std::string> lines;
    for (std::string l; std::getline(in, l);) lines.push_back(l);
    return lines;
}

void write_lines(const std::string& file, const std::vector<std::string>& lines) {
    std::ofstream out(file);
    for (const auto& l : lines) out << l << "\n";
}

class CandumpIdentify : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        std::ofstream(path("fw.yaml")) << kFirmwareConfig;
        std::ofstream(path("robot.yaml")) << kRobot;
        const auto r = run_command(jacobid("sim-can --robot " + path("robot.yaml") + " --config " + path("fw.yaml") + " --candump " +
                                           path("capture.log") + " --duration 30 --seed 4 --quiet"));
        ASSERT_EQ(r.exit_code, 0) << r.err;
    }
    static std::string identify(const std::string& capture, const std::string& extra = "") {
        return jacobid("identify --robot " + path("robot.yaml") + " --can-config " + path("fw.yaml") + " --in " + capture + " " + extra);
    }
};

TEST_F(CandumpIdentify, CaptureIsWhatPythonCanReads) {
    const std::string script = std::string(JACOBID_TESTS_DIR) + "/integration/stream/python_can_reader.py";
    const auto r = run_command(std::string("\"") + JACOBID_REFERENCE_PYTHON + "\" \"" + script + "\" \"" + path("capture.log") + "\"");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    std::istringstream in(r.out);
    std::size_t frames = 0;
    long long previous_us = -1;
    for (std::string line; std::getline(in, line); ++frames) {
        double t;
        long long us;
        int ext, remote, fd, error, brs, esi, dlc;
        unsigned id;
        char data[64];
        ASSERT_EQ(std::sscanf(line.c_str(), "%lf %lld %d %d %d %d %d %d %X %d %63s", &t, &us, &ext, &remote, &fd, &error, &brs, &esi, &id, &dlc, data), 11);
        EXPECT_EQ(id, 0u);  // MIT replies all come on id 0, the motor in data[0]
        EXPECT_EQ(dlc, 8);
        EXPECT_EQ(ext + remote + fd + error, 0);
        const unsigned motor = static_cast<unsigned>(std::stoul(std::string(data, 2), nullptr, 16));
        EXPECT_EQ(motor, frames % 2 + 1);
        // 1 kHz: both motors of a sample share its stamp, consecutive samples are 1000 us apart.
        if (frames % 2 == 0 && previous_us >= 0) {
            EXPECT_EQ(us - previous_us, 1000);
        }
        if (frames % 2 == 0) previous_us = us;
    }
    EXPECT_EQ(frames, 2u * 30001u);
}

TEST_F(CandumpIdentify, IdentificationFromTheCaptureMeetsTheBars) {
    const auto r = run_command(identify(path("capture.log"), "--format json --quiet"));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    jacobid::test::expect_table2_bars(j);
}

TEST_F(CandumpIdentify, LostCorruptAndForeignFramesAreHandledExplicitly) {
    auto lines = lines_of(path("capture.log"));
    ASSERT_GT(lines.size(), 2000u);
    // Lost frame: drop motor 2's reply of sample 500 (line 1002); motor 1 then sends again on line 1002.
    auto lost = lines;
    lost.erase(lost.begin() + 1001);
    write_lines(path("lost.log"), lost);
    auto r = run_command(identify(path("lost.log")));
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("lost.log:1002: joint 1 sends again (its previous frame is on line 1001) before joint(s) 2"), std::string::npos) << r.err;
    // Corrupt frame: motor 1's reply of sample 100 cut to 3 bytes.
    auto corrupt = lines;
    corrupt[200] = corrupt[200].substr(0, corrupt[200].find('#') + 7);
    write_lines(path("corrupt.log"), corrupt);
    r = run_command(identify(path("corrupt.log")));
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("corrupt.log:201: frame 0x0 of joint 1"), std::string::npos) << r.err;
    // Another device on the bus: skipped and counted, the identification is unaffected.
    auto foreign = lines;
    for (std::size_t i = 10; i < 20; ++i) foreign.insert(foreign.begin() + static_cast<std::ptrdiff_t>(2 * i), "(1700000000.010000) can0 1A0#00112233");
    write_lines(path("foreign.log"), foreign);
    r = run_command(identify(path("foreign.log"), "--format json"));
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("10 frames of other ids"), std::string::npos) << r.err;
}

// Issue 20: losing the frame of the joint that comes first in a cycle used to pair the other joint's frame
// with the first joint's frame of the next cycle, shifting that joint by a cycle for the rest of the
// capture (exit 0, only a warning about the last cycle).
TEST_F(CandumpIdentify, LostFirstFrameOfACycleIsAnErrorNotAShift) {
    auto lines = lines_of(path("capture.log"));
    ASSERT_GT(lines.size(), 2000u);
    lines.erase(lines.begin() + 1000);  // motor 1's reply of sample 500 (line 1001)
    write_lines(path("lost_first.log"), lines);
    const auto r = run_command(identify(path("lost_first.log")));
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("lost_first.log:1002: the frame of joint 1 is 1 ms after the cycle that began on line 1001"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("joint 1's frame of the cycle of line 1001 was lost"), std::string::npos) << r.err;
}

// Issue 20: two joints on one motor id were accepted; the first joint then took both motors' frames and
// a capture read as "a frame was lost".
TEST_F(CandumpIdentify, TwoJointsOnOneMotorIdAreRefusedWhenTheConfigIsRead) {
    std::string config = kFirmwareConfig;
    config.replace(config.find("motor_id: 2"), 11, "motor_id: 1");
    std::ofstream(path("same_id.yaml")) << config;
    for (const std::string& command :
         {jacobid("identify --robot " + path("robot.yaml") + " --can-config " + path("same_id.yaml") + " --in " + path("capture.log")),
          jacobid("sim-can --robot " + path("robot.yaml") + " --config " + path("same_id.yaml") + " --candump " + path("same_id.log") +
                  " --duration 1 --quiet")}) {
        const auto r = run_command(command);
        EXPECT_EQ(r.exit_code, 2) << command << "\n" << r.err;
        EXPECT_NE(r.err.find("same_id.yaml:4:5: joints[0] (shoulder) and joints[1] (elbow) listen to the same device (CAN id 0x0; motor_id: 1 "
                             "and motor_id: 1)"),
                  std::string::npos)
            << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    }
}

TEST_F(CandumpIdentify, SimCanNeedsExactlyOneOutput) {
    const auto r = run_command(jacobid("sim-can --duration 1"));
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("exactly one of --iface and --candump"), std::string::npos) << r.err;
}

}  // namespace
