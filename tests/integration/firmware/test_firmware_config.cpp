// SPDX-License-Identifier: MIT
// fw.yaml errors: one line naming the file, line, column and the key, for each kind of mistake.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "firmware_test_support.hpp"
#include "scratch_directory.hpp"

namespace {

using namespace jacobid;

std::string error_of(const std::string& yaml) {
    try {
        firmware::parse_firmware_config(yaml, "fw.yaml");
    } catch (const firmware::ConfigError& e) {
        return e.what();
    }
    return "(no error)";
}

const std::string kJoints =
    "joints:\n"
    "  - {profile: mit, motor_id: 1}\n"
    "  - {profile: mit, motor_id: 2}\n";
const std::string kCan = "can: {interface: can0}\n";
const std::string kStream = "stream: {host: 127.0.0.1, port: 5005}\n";

TEST(FirmwareConfig, ValidConfigAndDefaults) {
    const firmware::FirmwareConfig c = test::chain_config(
        "gpio: {chip: gpiochip0, estop_line: 4, enable_line: 5, sync_line: 6}\n"
        "realtime: {priority: 70, cpu: 1, report_period: 5}\n");
    EXPECT_EQ(c.can_interface, "virtual");
    EXPECT_EQ(c.rate, 1000.0);
    ASSERT_EQ(c.joints.size(), 2u);
    EXPECT_EQ(c.joints[0].name, "shoulder");
    const auto& m = std::get<hal::mit::JointConfig>(c.joints[1].decoder);
    EXPECT_EQ(m.motor_id, 2);
    EXPECT_EQ(m.mapping.gear_ratio, 4.0);
    EXPECT_EQ(m.ranges.t_max, 2.0);
    EXPECT_EQ(m.ranges.p_max, 12.5);  // default
    EXPECT_TRUE(c.gpio.enabled);
    EXPECT_EQ(c.gpio.sync_line, 6u);
    EXPECT_EQ(c.realtime.priority, 70);
    EXPECT_EQ(c.realtime.cpu, 1);
    const firmware::FirmwareConfig d = firmware::parse_firmware_config(kCan + kJoints + kStream, "fw.yaml");
    EXPECT_FALSE(d.gpio.enabled);
    EXPECT_EQ(d.estimator.velocity_window, 0.05);
    EXPECT_EQ(d.realtime.priority, 80);
    const firmware::FirmwareConfig o = firmware::parse_firmware_config(
        kCan + "joints:\n  - {profile: cia402, node_id: 3}\n  - {profile: odrive, node_id: 4, torque_constant: 0.1}\n" + kStream, "fw.yaml");
    EXPECT_EQ(std::get<hal::cia402::JointConfig>(o.joints[0].decoder).cob_id(), 0x183u);
    EXPECT_EQ(std::get<hal::odrive::JointConfig>(o.joints[1].decoder).mapping.torque_constant, 0.1);
}

TEST(FirmwareConfig, ErrorsNameTheKeyAndLine) {
    EXPECT_EQ(error_of(kJoints + kStream), "fw.yaml:1:1: can: missing (required): can: {interface: can0}");
    EXPECT_EQ(error_of(kCan + "joints:\n  - {profile: mit}\n  - {profile: mit, gear_ratio: 0}\n" + kStream),
              "fw.yaml:4:32: joints[1].gear_ratio: gear ratio must be finite and non-zero");
    EXPECT_EQ(error_of(kCan + "joints:\n  - {profile: mit, gear_ration: 4}\n" + kStream), "fw.yaml:3:20: joints[0].gear_ration: unknown key (known: direction, effort, effort_range, extended_id, gear_ratio, "
              "max_torque, max_velocity, motor_id, name, offset, position_range, profile, reply_id, require_status, "
              "torque_constant, velocity_range)");
    EXPECT_EQ(error_of(kCan + "joints:\n  - {profile: canopen}\n" + kStream),
              "fw.yaml:3:15: joints[0].profile: 'canopen' is not one of: mit, cia402, odrive");
    EXPECT_EQ(error_of(kCan + "joints:\n  - {motor_id: 1}\n" + kStream),
              "fw.yaml:3:5: joints[0].profile: missing (required): mit, cia402 or odrive");
    EXPECT_EQ(error_of(kCan + "joints:\n  - {profile: mit, effort_range: [8, -8]}\n" + kStream),
              "fw.yaml:3:34: joints[0].effort_range: need min < max, got [8, -8]");
    EXPECT_EQ(error_of(kCan + "joints:\n  - {profile: cia402, node_id: 200}\n" + kStream),
              "fw.yaml:3:32: joints[0].node_id: must be an integer in 1..127");
    EXPECT_EQ(error_of(kCan + "joints:\n  - {profile: cia402, effort: current, rated_current: 3}\n" + kStream),
              "fw.yaml:3:5: joints[0].torque_constant: required (N.m/A) with effort: current");
    EXPECT_EQ(error_of("rate: fast\n" + kCan + kJoints + kStream), "fw.yaml:1:7: rate: expected a number, got 'fast'");
    EXPECT_EQ(error_of(kCan + kJoints + "stream: {host: 127.0.0.1, port: 70000}\n"),
              "fw.yaml:5:33: stream.port: must be an integer in 1..65535");
    EXPECT_EQ(error_of(kCan + kJoints + "stream: {host: 127.0.0.1}\n"), "fw.yaml:5:9: stream.port: missing (required)");
    // An even number of samples per window puts a central estimate between two samples: not alignable.
    EXPECT_EQ(error_of(kCan + kJoints + kStream + "estimator:\n  velocity_window: 0.051\n"),
              "fw.yaml:7:20: estimator.velocity_window: kernel delays h(1-xi) must be whole numbers of samples to be aligned "
              "(use an odd tap count for central kernels)");
    EXPECT_EQ(error_of(kCan + kJoints + kStream + "estimator: {acceleration_window: 0.6}\n"),
              "fw.yaml:6:34: estimator.acceleration_window: window has more taps (round(T/Ts)+1) than the kernel capacity "
              "(at 1000 Hz; at most 512 taps)");
    EXPECT_EQ(error_of(kCan + kJoints + kStream + "gpio: {chip: gpiochip0, estop_line: 4, enable_line: 4, sync_line: 6}\n"),
              "fw.yaml:6:67: gpio.sync_line: estop_line, enable_line and sync_line must be different lines");
    EXPECT_EQ(error_of(kCan + kJoints + kStream + "realtime: {priority: 120}\n"), "fw.yaml:6:22: realtime.priority: must be an integer in 0..99");
    EXPECT_EQ(error_of(kCan + kJoints + kStream + "extra: 1\n"), "fw.yaml:6:1: extra: unknown key (known: can, estimator, gpio, joints, max_age, monitor, rate, realtime, stream, trajectory)");
    EXPECT_EQ(error_of("can: [\n"), "fw.yaml:2:1: invalid YAML: end of sequence flow not found");
    EXPECT_EQ(error_of(""), "fw.yaml: empty configuration");
    std::string nine = "joints:\n";
    for (int i = 0; i < 9; ++i) nine += "  - {profile: mit}\n";
    EXPECT_EQ(error_of(kCan + nine + kStream), "fw.yaml:3:3: joints: at most 8 joints");
}

TEST(FirmwareConfig, SyncIdIsOptionalHexOrDecimalAndAStandardId) {
    const std::string joints_stream = kJoints + kStream;
    EXPECT_EQ(firmware::parse_firmware_config(kCan + joints_stream, "fw.yaml").sync_id, -1);  // no SYNC unless asked
    EXPECT_EQ(firmware::parse_firmware_config("can: {interface: vcan0, sync_id: 0x080}\n" + joints_stream, "fw.yaml").sync_id, 0x80);
    EXPECT_EQ(firmware::parse_firmware_config("can: {interface: vcan0, sync_id: 129}\n" + joints_stream, "fw.yaml").sync_id, 129);
    EXPECT_EQ(error_of("can: {interface: vcan0, sync_id: 0x800}\n" + joints_stream), "fw.yaml:1:34: can.sync_id: must be an integer in 1..2047");
    EXPECT_EQ(error_of("can: {interface: vcan0, sync_id: 0}\n" + joints_stream), "fw.yaml:1:34: can.sync_id: must be an integer in 1..2047");
}

// Issue 36: a SYNC on the id of a joint's command or telemetry frames was accepted (the drive would read each
// SYNC as one of its frames). Refused at can.sync_id, naming the joint and its id keys; decided by the
// profiles' own encoders, for every profile.
TEST(FirmwareConfig, SyncIdOnAJointsCommandOrTelemetryIdIsRefusedNamingBothKeys) {
    EXPECT_EQ(error_of("can: {interface: vcan0, sync_id: 1}\n" + kJoints + kStream),
              "fw.yaml:1:34: can.sync_id: 0x1 is also the CAN id of joints[0] (j1)'s command frames (motor_id: 1): the drives would take each SYNC "
              "for one of those frames and those frames for SYNCs; give can.sync_id an id no joint uses (0x80 by convention)");
    EXPECT_EQ(error_of("can: {interface: vcan0, sync_id: 2}\n" + kJoints + kStream).rfind("fw.yaml:1:34: can.sync_id: 0x2 is also the CAN id of joints[1] (j2)'s command frames (motor_id: 2)", 0), 0u);
    const std::string cia = "joints:\n  - {profile: cia402, node_id: 3}\n";
    EXPECT_NE(error_of("can: {interface: vcan0, sync_id: 0x183}\n" + cia + kStream).find("0x183 is also the CAN id of joints[0] (j1)'s telemetry frames (node_id: 3)"),
              std::string::npos)
        << error_of("can: {interface: vcan0, sync_id: 0x183}\n" + cia + kStream);
    EXPECT_NE(error_of("can: {interface: vcan0, sync_id: 0x203}\n" + cia + kStream).find("0x203 is also the CAN id of joints[0] (j1)'s command frames (node_id: 3)"),
              std::string::npos)
        << error_of("can: {interface: vcan0, sync_id: 0x203}\n" + cia + kStream);
    const std::string odrive = "joints:\n  - {profile: odrive, node_id: 4}\n";
    EXPECT_NE(error_of("can: {interface: vcan0, sync_id: 0x8C}\n" + odrive + kStream).find("0x8C is also the CAN id of joints[0] (j1)'s command frames (node_id: 4)"),
              std::string::npos)
        << error_of("can: {interface: vcan0, sync_id: 0x8C}\n" + odrive + kStream);
    const std::string replies_on_0x80 = "can: {interface: vcan0, sync_id: 0x80}\njoints:\n  - {profile: mit, motor_id: 1, reply_id: 0x80}\n" + kStream;
    EXPECT_NE(error_of(replies_on_0x80).find("telemetry frames (motor_id: 1, reply_id: 0x80)"), std::string::npos) << error_of(replies_on_0x80);
    EXPECT_EQ(error_of("can: {interface: vcan0, sync_id: 0x80}\n" + cia + kStream), "(no error)") << "the CANopen SYNC id beside a CiA 402 node";
    EXPECT_EQ(error_of("can: {interface: vcan0, sync_id: 0x80}\n" + odrive + kStream), "(no error)");
}

// yaml-cpp keeps both entries of a repeated key and a lookup returns the first: an error instead.
TEST(FirmwareConfig, RepeatedKeyIsAnError) {
    EXPECT_EQ(error_of("can: {interface: vcan0, interface: can0}\n" + kJoints + kStream), "fw.yaml:1:25: can.interface: appears twice");
    EXPECT_EQ(error_of(kCan + "rate: 1000\nrate: 500\n" + kJoints + kStream), "fw.yaml:3:1: rate: appears twice");
}

// Issue 36: stream.log or trajectory.log onto fw.yaml itself or onto the trajectory table (also through a
// symlink or a hard link: compared as files), or both logs onto one file, is refused when fw.yaml is read,
// before jacobid-fw opens anything for writing. Output paths are relative to fw.yaml's folder, as the table's.
TEST(FirmwareConfig, AnOutputThatIsAnInputOrAnotherOutputIsRefusedAsAFile) {
    namespace fs = std::filesystem;
    const fs::path dir = test::scratch_directory() / "outputs";
    fs::create_directories(dir);
    std::ofstream(dir / "table.csv") << "t,q1,q2,qd1,qd2\n0,0,0,0,0\n0.001,0,0,0,0\n0.002,0,0,0,0\n";
    std::error_code ignored;
    fs::remove(dir / "fw-link.yaml", ignored);
    fs::remove(dir / "table-hard.csv", ignored);
    fs::create_symlink("fw.yaml", dir / "fw-link.yaml");
    fs::create_hard_link(dir / "table.csv", dir / "table-hard.csv");
    const std::string limits = "  joints:\n    - {position: [-1, 1], velocity: 1, acceleration: 10, torque: 1, following_error: 0.1, kp: 10, kd: 1}\n"
                               "    - {position: [-1, 1], velocity: 1, acceleration: 10, torque: 1, following_error: 0.1, kp: 10, kd: 1}\n";
    auto error_with = [&](const std::string& stream_log, const std::string& trajectory_log) {
        const std::string config = (dir / "fw.yaml").string();
        std::string stream = kStream;
        if (!stream_log.empty()) stream = "stream: {host: 127.0.0.1, port: 5005, log: " + stream_log + "}\n";
        std::ofstream(config) << kCan + kJoints + stream + "trajectory:\n  file: table.csv\n" +
                                     (trajectory_log.empty() ? "" : "  log: " + trajectory_log + "\n") + limits;
        try {
            firmware::load_firmware_config(config);
        } catch (const firmware::ConfigError& e) {
            return std::string(e.what());
        }
        return std::string("(no error)");
    };
    const std::string config = (dir / "fw.yaml").string(), folder = dir.string() + "/";
    EXPECT_EQ(error_with("fw.yaml", ""), config + ":5:44: stream.log: '" + folder + "fw.yaml' is the same file as this configuration file ('" + config +
                                             "'): writing there would overwrite that input; give another file");
    EXPECT_NE(error_with("fw-link.yaml", "").find("stream.log: '" + folder + "fw-link.yaml' is the same file as this configuration file"), std::string::npos)
        << error_with("fw-link.yaml", "");
    EXPECT_NE(error_with("", "table-hard.csv").find(":8:8: trajectory.log: '" + folder + "table-hard.csv' is the same file as trajectory.file ('" +
                                                    folder + "table.csv')"),
              std::string::npos)
        << error_with("", "table-hard.csv");
    EXPECT_NE(error_with("", "../outputs/fw.yaml").find("trajectory.log: '" + folder + "../outputs/fw.yaml' is the same file as this configuration file"),
              std::string::npos)
        << error_with("", "../outputs/fw.yaml");
    EXPECT_NE(error_with("out.bin", "./out.bin").find("trajectory.log: '" + folder + "./out.bin' is the same file as stream.log ('" + folder +
                                                       "out.bin'): give each output its own file"),
              std::string::npos)
        << error_with("out.bin", "./out.bin");
    EXPECT_EQ(error_with("stream.bin", "commands.csv"), "(no error)");
    EXPECT_EQ(firmware::load_firmware_config(config).stream.log, folder + "stream.bin") << "relative to fw.yaml's folder, as every path in it";
}

// Issue 36's audit of fw.yaml: values a careless user gives that were accepted and gave a wrong, unsafe or
// undefined result, each refused at its key.
TEST(FirmwareConfig, CarelessValuesAreRefusedAtTheirKey) {
    const std::string head = kCan + kJoints + kStream;
    // rate: 1e12 Hz was blamed on estimator.position_window (at line 1:1, a key not in the file).
    EXPECT_EQ(error_of("rate: 1e12\n" + head), "fw.yaml:1:7: rate: 1e+12 Hz: expected a control rate in [1, 10000] Hz");
    EXPECT_EQ(error_of("rate: 0.5\n" + head), "fw.yaml:1:7: rate: 0.5 Hz: expected a control rate in [1, 10000] Hz");
    // report_period: 1e300 s overflowed the report deadline (int64), 1e-9 s printed a report every cycle.
    EXPECT_EQ(error_of(head + "realtime: {report_period: 1e300}\n"),
              "fw.yaml:6:27: realtime.report_period: 1e+300 s: expected 0 (only at exit) or a period in [0.1, 1e+09] s");
    EXPECT_NE(error_of(head + "realtime: {report_period: 1e-9}\n").find("realtime.report_period: 1e-09 s: expected 0"), std::string::npos);
    EXPECT_EQ(firmware::parse_firmware_config(head + "realtime: {report_period: 0}\n", "fw.yaml").realtime.report_period, 0.0);

    const std::string table = (test::scratch_directory() / "careless.csv").string();
    std::ofstream(table) << "t,q1,q2,qd1,qd2\n0,0,0,0,0\n0.001,0,0,0,0\n0.002,0,0,0,0\n";
    auto trajectory = [&](const std::string& settings, const std::string& joint1) {
        return head + "trajectory:\n  file: " + table + "\n" + settings + "  joints:\n    - " + joint1 +
               "\n    - {position: [-1, 1], velocity: 1, acceleration: 10, torque: 1, following_error: 0.1, kp: 10, kd: 1}\n";
    };
    const std::string ok = "{position: [-1, 1], velocity: 1, acceleration: 10, torque: 1, following_error: 0.1, kp: 10, kd: 1}";
    EXPECT_EQ(error_of(trajectory("", ok)), "(no error)");
    // ramp_time: 1e300 s overflowed the ramp's cycle count; 5000 is 5 s written in ms.
    EXPECT_EQ(error_of(trajectory("  ramp_time: 5000\n", ok)), "fw.yaml:8:14: trajectory.ramp_time: 5000 s: expected at most 3600 s (in seconds, not ms)");
    EXPECT_NE(error_of(trajectory("  ramp_time: 1e300\n", ok)).find("trajectory.ramp_time: 1e+300 s: expected at most 3600 s"), std::string::npos);
    // A following error as wide as the position range never stops anything.
    EXPECT_NE(error_of(trajectory("", "{position: [-1, 1], velocity: 1, acceleration: 10, torque: 1, following_error: 5, kp: 10, kd: 1}"))
                  .find("trajectory.joints[0].following_error: 5 rad is not below the width of the position limits, 2 rad: it could never stop the playback"),
              std::string::npos);
    // No kp, kd with an MIT drive in position mode: every command frame said "torque only" (kp = kd = 0),
    // so the drive held no position, and neither did the stop.
    const std::string limp = error_of(trajectory("", "{position: [-1, 1], velocity: 1, acceleration: 10, torque: 1, following_error: 0.1}"));
    EXPECT_NE(limp.find("trajectory.joints[0].kp: with kp: 0 and kd: 0 joints[0]'s mit drive reads each position command as a torque command"),
              std::string::npos)
        << limp;
    EXPECT_EQ(error_of(trajectory("  mode: torque\n", "{position: [-1, 1], velocity: 1, acceleration: 10, torque: 1, following_error: 0.1}")).find("kp"),
              std::string::npos)
        << "torque mode needs no gains";
    // A limit beyond what the joint's command frames carry: an MIT position, velocity, torque or gain beyond its
    // range was clamped by the encoder (exit 0 with other commands than the table's). Refused at the key;
    // a limit at the range's edge, a value merely quantized, and fields a profile does not send are not.
    auto uncarried = [&](const std::string& joint1) { return error_of(trajectory("", joint1)); };
    EXPECT_NE(uncarried("{position: [-10, 10], velocity: 1, acceleration: 10, torque: 1, following_error: 0.1, kp: 10, kd: 1}")
                  .find("trajectory.joints[0].position: -10 cannot be sent to joints[0]'s mit drive: its command frames carry -"),
              std::string::npos)
        << uncarried("{position: [-10, 10], velocity: 1, acceleration: 10, torque: 1, following_error: 0.1, kp: 10, kd: 1}");
    EXPECT_NE(uncarried("{position: [-1, 1], velocity: 1, acceleration: 10, torque: 1, following_error: 0.1, kp: 5000, kd: 1}")
                  .find("trajectory.joints[0].kp: 5000 cannot be sent to joints[0]'s mit drive: its command frames carry 500 there (the encoder saturates)"),
              std::string::npos);
    EXPECT_NE(uncarried("{position: [-1, 1], velocity: 1000, acceleration: 10, torque: 1, following_error: 0.1, kp: 10, kd: 1}").find("trajectory.joints[0].velocity: -1000"),
              std::string::npos);
    EXPECT_NE(uncarried("{position: [-1, 1], velocity: 1, acceleration: 10, torque: 1e4, following_error: 0.1, kp: 10, kd: 1}").find("trajectory.joints[0].torque: -10000"),
              std::string::npos);
    EXPECT_EQ(uncarried("{position: [-1, 1], velocity: 1, acceleration: 10, torque: 1, following_error: 0.1, kp: 10, kd: 0.0013}"), "(no error)");
    EXPECT_EQ(uncarried("{position: [-3.125, 3.125], velocity: 16.25, acceleration: 10, torque: 120, following_error: 0.1, kp: 500, kd: 5}"), "(no error)")
        << "the MIT ranges' edges at gear 4 (12.5 rad, 65 rad/s, 30 N.m motor side; kp 0..500, kd 0..5)";
    // CiA 402 wraps its position (a modulo counter) and sends no velocity or torque in position mode: nothing saturates.
    const std::string one_joint = (test::scratch_directory() / "careless1.csv").string();
    std::ofstream(one_joint) << "t,q1,qd1\n0,0,0\n0.001,0,0\n";
    EXPECT_EQ(error_of(kCan + "joints:\n  - {profile: cia402, node_id: 3}\n" + kStream + "trajectory:\n  file: " + one_joint +
                       "\n  joints:\n    - {position: [-1000, 1000], velocity: 1000, acceleration: 10, torque: 1000, following_error: 0.1}\n"),
              "(no error)");
    // A table for three joints on a two-joint config: q3, qd3 were dropped silently.
    std::ofstream(table) << "t,q1,q2,q3,qd1,qd2,qd3\n0,0,0,0,0,0,0\n0.001,0,0,0,0,0,0\n";
    EXPECT_EQ(error_of(trajectory("", ok)), table + ":1:4: column 'q3' is for joint 3, but fw.yaml has 2 joints: a table for another robot? (its values "
                                                    "would not be played)");
}

TEST(FirmwareConfig, MissingFileIsNamed) {
    try {
        firmware::load_firmware_config("/nonexistent/fw.yaml");
        FAIL();
    } catch (const firmware::ConfigError& e) {
        EXPECT_STREQ(e.what(), "/nonexistent/fw.yaml: cannot open the configuration file");
    }
}

// Fuzzing (fuzz/targets/fuzz_firmware_config.cpp) found this input, here byte for byte: a flow list in key
// position ("mit,[ motor_id: 1, ...]") made the unknown-key check throw yaml-cpp's bad conversion instead
// of a ConfigError. The error now points at the '[' (line 4, column 35).
TEST(FirmwareConfig, FuzzRegressionListUsedAsAKeyIsAConfigError) {
    const std::string input =
        "can: {interface: virtual}\nrate: 1000\njoints:\n"
        "  - {name: shoulder, profile: mit,[ motor_id: 1, gear_ratio: 4, velocity_range: [-65, 65], efforequire_status, 30]}\n"
        "  - {name: elbow, profile: mit, motor_id:elbow, profile: mit, motor_id: 2, gear_ratio: 4, velocityp0, estop_line: 4, enab 70, "
        "cpu: 1, report.02, velocitdow: 0.05, acceleration_window: 0.1}\n"
        "stream: {host: 127.0.0.1, port:\xff\xff" "can\xff*5}\n:gpio";
    ASSERT_EQ(input.size(), 396u);
    EXPECT_EQ(error_of(input), "fw.yaml:4:35: joints[0]: expected a key name, found a list or map used as a key");
    EXPECT_EQ(error_of(kCan + "joints:\n  - {profile: mit, {a: 1}: 2}\n" + kStream),
              "fw.yaml:3:20: joints[0]: expected a key name, found a list or map used as a key");
}

}  // namespace
