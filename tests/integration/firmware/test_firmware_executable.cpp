// SPDX-License-Identifier: MIT
// The jacobid-fw and `jacobid sim-can` executables: help, configuration and device errors, and a dry run
// of the real cycle loop (clock_nanosleep, UDP, SIGTERM, jitter statistics) into `jacobid record`.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <unistd.h>

#include "firmware_test_support.hpp"
#include "run_command.hpp"
#include "scratch_directory.hpp"
#include "../stream/stream_test_support.hpp"

namespace {

using namespace jacobid;
using test::run_command;

std::string path(const std::string& name) { return (test::scratch_directory() / name).string(); }
std::string fw(const std::string& args) { return std::string(JACOBID_FW_EXECUTABLE) + " " + args; }
std::string jacobid(const std::string& args) { return std::string(JACOBID_EXECUTABLE) + " " + args; }

TEST(FirmwareExecutable, HelpListsTheOptions) {
    const auto r = run_command(fw("--help"));
    EXPECT_EQ(r.exit_code, 0);
    EXPECT_NE(r.out.find("--config"), std::string::npos);
    EXPECT_NE(r.out.find("SIGUSR1"), std::string::npos);
}

TEST(FirmwareExecutable, ConfigErrorExitsTwoNamingKeyAndLine) {
    std::ofstream(path("bad.yaml")) << "can: {interface: can0}\njoints:\n  - {profile: mit, gear_ratio: 0}\nstream: {host: 127.0.0.1, port: 5005}\n";
    const auto r = run_command(fw("--config " + path("bad.yaml")));
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("bad.yaml:3:32: joints[0].gear_ratio: gear ratio must be finite and non-zero"), std::string::npos) << r.err;
}

// Issue 20: --duration -1 meant "run until a signal" (any value <= 0 did), nan too, and 1e12 s overflowed the
// deadline in nanoseconds; CLI11's own errors exited 105-109 on two lines. All are one-line exit-2 errors now.
TEST(FirmwareExecutable, InvalidDurationAndParseErrorsExitTwoOnOneLine) {
    std::ofstream(path("ok.yaml")) << test::chain_config_yaml();
    for (const std::string value : {"-1", "nan", "inf", "1e12", "abc"}) {
        const auto r = run_command("timeout 5 " + fw("--config " + path("ok.yaml") + " --no-realtime --duration " + value));
        EXPECT_EQ(r.exit_code, 2) << value << ": " << r.err;
        EXPECT_EQ(r.err.rfind("jacobid-fw: error: --duration: expected a number of seconds in [0, 1e9]", 0), 0u) << value << ": " << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    }
    const auto unknown = run_command(fw("--config " + path("ok.yaml") + " --bogus"));
    EXPECT_EQ(unknown.exit_code, 2) << unknown.err;
    EXPECT_EQ(unknown.err.rfind("jacobid-fw: error: ", 0), 0u) << unknown.err;
    EXPECT_NE(unknown.err.find("--bogus"), std::string::npos) << unknown.err;
}

// Issue 36: a table with a 2 rad jump between two rows (each row within the limits), and one that does not
// end where it starts played with repeat: 3, are refused before jacobid-fw opens the bus or any output:
// exit 2, one line naming the table's line, the joint, the step and the limit, and neither stream.log nor
// trajectory.log created.
void expect_refused_before_anything_is_opened(const std::string& table, const std::string& settings, const std::string& message) {
    std::remove(path("unsafe_stream.bin").c_str());
    std::remove(path("unsafe_commands.csv").c_str());
    std::string yaml = test::chain_config_yaml(
        "trajectory:\n  file: " + table + "\n  log: unsafe_commands.csv\n" + settings + "  joints:\n"
        "    - {position: [-3, 3], velocity: 3, acceleration: 10, torque: 100, following_error: 0.01, kp: 10, kd: 1}\n"
        "    - {position: [-3, 3], velocity: 3, acceleration: 10, torque: 8, following_error: 0.01, kp: 10, kd: 1}\n");
    yaml.replace(yaml.find("port: 5005}"), 11, "port: 5005, log: unsafe_stream.bin}");
    std::ofstream(path("unsafe.yaml")) << yaml;
    const auto r = run_command("timeout 10 " + fw("--config " + path("unsafe.yaml") + " --no-realtime --duration 1"));
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_EQ(r.err.rfind("jacobid-fw: error: " + path(table) + message, 0), 0u) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(std::ifstream(path("unsafe_stream.bin")).good()) << "stream.log opened";
    EXPECT_FALSE(std::ifstream(path("unsafe_commands.csv")).good()) << "trajectory.log opened";
}

TEST(FirmwareExecutable, UnsafeTrajectoryIsRefusedOnOneLineBeforeAnythingIsOpened) {
    {
        std::ofstream jump(path("jump.csv"));
        jump << "t,q1,q2,qd1,qd2\n";
        for (int k = 0; k < 2000; ++k) jump << k * 1e-3 << ',' << (k < 1000 ? 0.0 : 2.0) << ",0,0,0\n";
        // 0 -> 0.4 rad in 1 s, at rest at both ends (q = 0.2 (1 - cos(pi t))): no jump, but no way back.
        std::ofstream half(path("half.csv"));
        half.precision(17);
        half << "t,q1,q2,qd1,qd2\n";
        for (int k = 0; k <= 1000; ++k) {
            const double t = k * 1e-3, pi = 3.14159265358979323846;
            half << t << ',' << 0.2 * (1.0 - std::cos(pi * t)) << ",0," << 0.2 * pi * std::sin(pi * t) << ",0\n";
        }
    }
    expect_refused_before_anything_is_opened("jump.csv", "",
                                             ":1002: joint 1: the position steps 2 rad from line 1001, 2000 rad/s at 1000 Hz, beyond the velocity "
                                             "limit 3 rad/s (trajectory.joints[0].velocity, +1 %)\n");
    expect_refused_before_anything_is_opened("half.csv", "  repeat: 3\n",
                                             ":2: joint 1: the position steps -0.4 rad from line 1002, -400 rad/s at 1000 Hz, beyond the velocity "
                                             "limit 3 rad/s (trajectory.joints[0].velocity, +1 %); this is the wrap from the table's last row "
                                             "(line 1002) to its next pass (repeat: 3)");
}

// Issue 36: stream.log through a symlink to fw.yaml itself: refused (exit 2, one line) and fw.yaml intact.
TEST(FirmwareExecutable, AStreamLogOntoItsOwnConfigIsRefusedAndTheConfigIsIntact) {
    std::string yaml = test::chain_config_yaml();
    yaml.replace(yaml.find("port: 5005}"), 11, "port: 5005, log: self-link.bin}");
    std::ofstream(path("self.yaml")) << yaml;
    std::remove(path("self-link.bin").c_str());
    ASSERT_EQ(::symlink("self.yaml", path("self-link.bin").c_str()), 0);
    const auto r = run_command("timeout 10 " + fw("--config " + path("self.yaml") + " --no-realtime --duration 0.2"));
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find("stream.log: '" + path("self-link.bin") + "' is the same file as this configuration file"), std::string::npos) << r.err;
    std::ifstream in(path("self.yaml"));
    const std::string after((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_EQ(after, yaml) << "fw.yaml overwritten";
}

// Issue 36's audit: a playback on a real bus without a gpio: section has no e-stop input and no drive
// enable; said before the bus is opened (here it cannot be: exit 1 naming the interface after the warning).
TEST(FirmwareExecutable, PlaybackWithoutSafetyIoIsWarnedBeforeTheBusIsOpened) {
    std::ofstream(path("quiet.csv")) << "t,q1,q2,qd1,qd2\n0,0,0,0,0\n0.001,0,0,0,0\n0.002,0,0,0,0\n";
    std::string yaml = test::chain_config_yaml(
        "trajectory:\n  file: quiet.csv\n  joints:\n"
        "    - {position: [-3, 3], velocity: 3, acceleration: 10, torque: 100, following_error: 0.01, kp: 10, kd: 1}\n"
        "    - {position: [-3, 3], velocity: 3, acceleration: 10, torque: 8, following_error: 0.01, kp: 10, kd: 1}\n");
    yaml.replace(0, std::string("can: {interface: virtual}").size(), "can: {interface: jacobidnocan0}");
    std::ofstream(path("quiet.yaml")) << yaml;
    const auto r = run_command(fw("--config " + path("quiet.yaml") + " --no-realtime --duration 0.2"));
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_EQ(r.err.rfind("jacobid-fw: warning: " + path("quiet.yaml") + ": trajectory playback without a gpio: section: no e-stop input", 0), 0u) << r.err;
    EXPECT_NE(r.err.find("can.interface 'jacobidnocan0'"), std::string::npos) << r.err;
}

// A trajectory.log that cannot be opened: exit 1, one error line naming fw.yaml and the key, as for stream.log.
TEST(FirmwareExecutable, ATrajectoryLogThatCannotBeOpenedIsAnErrorNamingTheConfig) {
    std::ofstream(path("unopened.csv")) << "t,q1,q2,qd1,qd2\n0,0,0,0,0\n0.001,0,0,0,0\n";
    std::ofstream(path("unopened.yaml")) << test::chain_config_yaml(
        "trajectory:\n  file: unopened.csv\n  log: /proc/jacobid-no-such-dir/commands.csv\n  joints:\n"
        "    - {position: [-3, 3], velocity: 3, acceleration: 10, torque: 100, following_error: 0.01, kp: 10, kd: 1}\n"
        "    - {position: [-3, 3], velocity: 3, acceleration: 10, torque: 8, following_error: 0.01, kp: 10, kd: 1}\n");
    const auto r = run_command(fw("--config " + path("unopened.yaml") + " --no-realtime --duration 0.2"));
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_NE(r.err.find("jacobid-fw: error: " + path("unopened.yaml") + ": trajectory.log /proc/jacobid-no-such-dir/commands.csv: "), std::string::npos) << r.err;
}

TEST(FirmwareExecutable, MissingCanInterfaceIsAClearDeviceError) {
    std::ofstream(path("can.yaml")) << test::chain_config_yaml().replace(0, std::string("can: {interface: virtual}").size(),
                                                                          "can: {interface: jacobidnocan0}");
    const auto r = run_command(fw("--config " + path("can.yaml") + " --no-realtime"));
    EXPECT_EQ(r.exit_code, 1);
    // This kernel has no CAN at all; with CAN but without the interface the reason differs. Both name it.
    EXPECT_NE(r.err.find("can.interface 'jacobidnocan0'"), std::string::npos) << r.err;
}

TEST(FirmwareExecutable, DryRunLoopStreamsUntilSigtermAndPrintsJitter) {
    // record (idle timeout ends it) first, on a port it picks; the firmware is started once record says it
    // listens (waited for, with a timeout, not a pause) and is stopped by SIGTERM after ~1 s.
    test::Recorder recorder({"record", "--quiet", "--on-gap", "mark", "--idle-timeout", "1", "--udp", "127.0.0.1:0", "-o", path("dry.csv"),
                             "--summary", path("dry.json")},
                            path("record.err"));
    const int port = recorder.wait_for_port();
    std::string yaml = test::chain_config_yaml("realtime: {report_period: 0.2}\n");
    yaml.replace(yaml.find("port: 5005"), 10, "port: " + std::to_string(port));
    std::ofstream(path("dry.yaml")) << yaml;
    const auto r = run_command("(timeout --preserve-status -s TERM 1.2 " + fw("--config " + path("dry.yaml")) + "; echo fw-exit=$?)");
    EXPECT_EQ(recorder.wait(30.0), 0) << recorder.err();
    EXPECT_NE(r.out.find("fw-exit=0"), std::string::npos) << r.out << r.err;
    EXPECT_NE(r.err.find("stopped (SIGTERM)"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("latency us: min"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("p99"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("real-time: SCHED_FIFO"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("dry run"), std::string::npos) << r.err;
    std::ifstream in(path("dry.json"));
    ASSERT_TRUE(in.good()) << r.err;
    const auto s = nlohmann::json::parse(in);
    const auto received = s["datagrams"]["received"].get<std::uint64_t>();
    EXPECT_GT(received, 500u) << s.dump(2);  // ~1 s at 1 kHz minus the 50-sample delay
    EXPECT_EQ(s["datagrams"]["lost"].get<std::uint64_t>(), 0u) << s.dump(2);
    // No device answers on the dry-run bus: every row is flagged stale, none passes as a measurement.
    EXPECT_EQ(s["rows"]["stale"].get<std::uint64_t>(), received) << s.dump(2);
}

TEST(SimCanCommand, HelpAndNoCanOnThisKernel) {
    const auto h = run_command(jacobid("sim-can --help"));
    EXPECT_EQ(h.exit_code, 0);
    EXPECT_NE(h.out.find("--iface"), std::string::npos);
    EXPECT_NE(h.out.find("--profile"), std::string::npos);
    const auto r = run_command(jacobid("sim-can --robot /nonexistent.yaml --iface vcan0 --duration 1"));
    EXPECT_EQ(r.exit_code, 2);
    const auto v = run_command(jacobid("sim-can --iface jacobidnocan0 --duration 1 --profile mit"));
    EXPECT_EQ(v.exit_code, 2);
    EXPECT_NE(v.err.find("--iface jacobidnocan0: "), std::string::npos) << v.err;
    EXPECT_EQ(v.err.find('\n'), v.err.size() - 1) << "one-line message: " << v.err;
}

}  // namespace
