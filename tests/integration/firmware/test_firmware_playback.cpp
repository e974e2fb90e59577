// SPDX-License-Identifier: MIT
// Trajectory playback through the whole firmware cycle on the virtual bus (issue 17): fw.yaml's
// `trajectory:` section, the table read at start-up, every cycle's MIT command frames decoded back on the
// drive side, and an ideal drive (it reaches each command by the next sample) closing the loop. Checked:
// the drives receive the ramp then the table rows (to the MIT position code's resolution, 9.5e-5 rad),
// and each injected fault (e-stop line, drive fault code, a silent joint) turns the very next command
// frames into a hold where the joints stand.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "allocation_counter.hpp"
#include "firmware_test_support.hpp"
#include "jacobid/firmware/runtime.hpp"
#include "jacobid/hal/profile_registry.hpp"
#include "scratch_directory.hpp"
#include "sim/can_player.hpp"

namespace {

using namespace jacobid;

constexpr std::int64_t kPeriodNs = 1'000'000;
constexpr double kPi = 3.14159265358979323846;
constexpr double kCode = 25.0 / 65535.0 / 4.0;  // one MIT position code on the link (fw chain config)

// One 2 s period at 1 kHz, at rest at both ends: q_j = c_j + a_j (1 - cos(2 pi t / 2)).
std::string write_table() {
    const std::string path = (test::scratch_directory() / "playback.csv").string();
    std::ofstream out(path);
    out.precision(17);
    out << "t,q1,q2,qd1,qd2,qdd1,qdd2\n";
    for (int k = 0; k <= 2000; ++k) {
        const double t = k * 1e-3, w = kPi;
        out << t << ',' << 0.2 + 0.5 * (1 - std::cos(w * t)) << ',' << -0.3 + 0.4 * (1 - std::cos(w * t)) << ',' << 0.5 * w * std::sin(w * t) << ','
            << 0.4 * w * std::sin(w * t) << ',' << 0.5 * w * w * std::cos(w * t) << ',' << 0.4 * w * w * std::cos(w * t) << '\n';
    }
    return path;
}

std::string playback_yaml() {
    return "trajectory:\n"
           "  file: " + write_table() + "\n"
           "  ramp_time: 0.5\n"
           "  repeat: 2\n"
           "  joints:\n"
           "    - {position: [-2, 2], velocity: 3, acceleration: 10, torque: 100, following_error: 0.01, kp: 40, kd: 1}\n"
           "    - {position: [-2, 2], velocity: 3, acceleration: 10, torque: 8, following_error: 0.01, kp: 10, kd: 0.5}\n";
}

// Keeps every record the cycle hands out (reserved up front: the cycle's step() must not allocate).
struct MemoryCommandLog final : firmware::CommandLog {
    std::vector<firmware::CommandRecord> records;
    MemoryCommandLog() { records.reserve(20000); }
    void record(const firmware::CommandRecord& r) noexcept override {
        if (records.size() < records.capacity()) records.push_back(r);
    }
};

struct PlaybackRig : test::BenchWiring {
    test::MemoryPublisher publisher;
    firmware::FirmwareConfig config = test::chain_config(playback_yaml());
    std::vector<hal::ProfileConfig> profiles = test::profiles_of(config);
    std::unique_ptr<firmware::FirmwareCycle> cycle = std::make_unique<firmware::FirmwareCycle>(*fw_end, publisher, &safety);
    sim::CanPlayer telemetry{*sim_end, profiles};
    double q[2] = {0.05, -0.1};  // where the robot stands before playback
    double reported[2] = {0.0, 0.0};  // the last position each drive sent
    std::vector<std::array<hal::JointCommand, 2>> received;  // per cycle, what the drives read
    std::uint64_t k = 0;
    bool drive_fault = false;  // joint 2 reports a fault code
    bool joint2_silent = false;
    std::uint64_t step_allocations = 0;  // heap allocations inside the firmware's step()

    MemoryCommandLog log;
    std::string configured;  // configure()'s answer ("" unless `edit` made the config unsafe)
    std::uint64_t frames_at_drives = 0;  // every frame the drives' end of the bus received

    // `edit` changes the parsed configuration before the cycle is configured (a table fw.yaml's parser
    // would already refuse, to test the cycle's own gate).
    explicit PlaybackRig(void (*edit)(firmware::FirmwareConfig&) = nullptr) {
        if (edit != nullptr) edit(config);
        configured = cycle->configure(config);
        if (edit == nullptr) {
            EXPECT_EQ(configured, "");
        }
        cycle->set_command_log(&log);
        EXPECT_TRUE(cycle->reset_estop());
    }
    void tick() {
        // The drive side: the commands of the last cycle, then this sample's telemetry.
        std::array<hal::JointCommand, 2> got{};
        std::array<bool, 2> seen{};
        hal::CanFrame f;
        while (sim_end->receive(f) == hal::CanStatus::Ok) {
            ++frames_at_drives;
            for (std::size_t j = 0; j < 2; ++j) {
                hal::JointCommand c;
                if (hal::decode_command(profiles[j], hal::CommandMode::Position, f, c) == hal::DecodeStatus::Ok) {
                    got[j] = c;
                    seen[j] = true;
                }
            }
        }
        if (seen[0] || seen[1]) {
            EXPECT_TRUE(seen[0] && seen[1]) << "cycle " << k << ": every joint is commanded in every cycle";
            received.push_back(got);
            for (std::size_t j = 0; j < 2; ++j) q[j] = got[j].position;  // the ideal drive
        }
        const std::int64_t now = static_cast<std::int64_t>(k) * kPeriodNs + 1'000'000'000;
        bus.set_time_ns(now);
        double qd[2] = {0, 0}, tau[2] = {0, 0};
        hal::CanFrame frames[hal::kMaxTelemetryFrames];
        for (std::size_t j = 0; j < 2; ++j) {
            if (j == 1 && joint2_silent) continue;
            reported[j] = q[j];
            const std::size_t n = telemetry.encode(j, q[j], qd[j], tau[j], frames);
            for (std::size_t i = 0; i < n; ++i) {
                if (j == 1 && drive_fault) frames[i].data[7] = 0x01;  // MIT byte 7: the drive's error code
                sim_end->send(frames[i]);
            }
        }
        const std::uint64_t before = test::allocation_count();
        cycle->step(now);
        step_allocations += test::allocation_count() - before;
        ++k;
    }
    void run(int n) {
        for (int i = 0; i < n; ++i) tick();
    }
};

TEST(FirmwarePlayback, DrivesReceiveTheRampThenEveryRowTwice) {
    PlaybackRig rig;
    ASSERT_TRUE(rig.cycle->playback());
    rig.run(1 + 500 + 2 * 2000 + 50);
    const auto& p = rig.cycle->player();
    EXPECT_EQ(p.phase(), firmware::PlaybackPhase::Finished) << firmware::to_string(p.stop_reason());
    // Cycle 1 has no measurement yet; the ramp starts at cycle 2 from the measured pose.
    ASSERT_GE(rig.received.size(), 500u + 4000u);
    EXPECT_NEAR(rig.received[0][0].position, 0.05, 2 * kCode) << "the ramp starts where the robot stands";
    EXPECT_NEAR(rig.received[0][1].kp, 10.0, 500.0 / 4095.0) << "the drive's own gains, from fw.yaml (to one 12-bit kp code)";
    const auto& rows = p.config().rows;
    EXPECT_NEAR(rig.received[499][0].position, rows[0].q[0], kCode) << "the ramp ends on the table's first row";
    double worst = 0.0;
    for (std::size_t c = 0; c < 4000; ++c) {
        // After the ramp: rows 1..2000, then (the table is closed) rows 1..2000 again.
        const std::size_t row = c % 2000 + 1;
        for (std::size_t j = 0; j < 2; ++j) worst = std::max(worst, std::abs(rig.received[500 + c][j].position - rows[row].q[j]));
        EXPECT_NEAR(rig.received[500 + c][0].velocity, rows[row].qd[0], 0.01) << "cycle " << c;
    }
    EXPECT_LE(worst, kCode) << "every command is its row, to one position code";
    // Finished: the last row is held.
    EXPECT_NEAR(rig.received.back()[0].position, rows.back().q[0], kCode);
    EXPECT_EQ(rig.cycle->counters().stop_cycles, 0u);
    EXPECT_EQ(rig.step_allocations, 0u) << "playback allocates nothing in the cycle";
    // The command log: one record per commanding cycle, what was sent beside what was measured then.
    ASSERT_EQ(rig.log.records.size(), rig.received.size() + 1) << "the drives read the last cycle's frames in a tick not run";
    for (std::size_t c = 1; c < rig.received.size(); ++c) {
        const firmware::CommandRecord& r = rig.log.records[c];
        EXPECT_NEAR(r.position[1], rig.received[c][1].position, kCode) << "record " << c;
        // The ideal drive reached the previous command: measured = previous command, to one code.
        EXPECT_NEAR(r.measured[0], rig.log.records[c - 1].position[0], kCode) << "record " << c;
    }
    EXPECT_EQ(rig.log.records[600].phase, firmware::PlaybackPhase::Playing);
    EXPECT_EQ(rig.log.records[600].row, 101u) << "records 0..499 are the ramp, 500 is row 1";
}

// Runs into the middle of the table, injects a fault, and checks that the next frames the drives read are
// the hold at the pose the drives last reported.
void expect_hold_after(void (*inject)(PlaybackRig&), firmware::StopReason reason, int joint) {
    PlaybackRig rig;
    rig.run(1 + 500 + 700);
    ASSERT_EQ(rig.cycle->player().phase(), firmware::PlaybackPhase::Playing);
    inject(rig);
    rig.tick();  // the cycle that reads the fault
    // Where the drives last said they stood (a silent joint: its last report).
    const double at_fault[2] = {rig.reported[0], rig.reported[1]};
    EXPECT_EQ(rig.cycle->player().phase(), firmware::PlaybackPhase::Stopped);
    EXPECT_EQ(rig.cycle->player().stop_reason(), reason) << firmware::to_string(rig.cycle->player().stop_reason());
    EXPECT_EQ(rig.cycle->player().stop_joint(), joint);
    rig.tick();  // the drives read what that cycle sent
    const auto& hold = rig.received.back();
    for (std::size_t j = 0; j < 2; ++j) {
        EXPECT_NEAR(hold[j].position, at_fault[j], kCode) << "joint " << j + 1 << " is held where it stood";
        EXPECT_NEAR(hold[j].velocity, 0.0, 0.01);
    }
    rig.run(20);
    EXPECT_EQ(rig.cycle->counters().stop_cycles, 22u) << "the hold is sent every cycle, latched";
    EXPECT_EQ(rig.step_allocations, 0u);
}

TEST(FirmwarePlayback, EachFaultTurnsTheNextCommandsIntoAHold) {
    expect_hold_after([](PlaybackRig& r) { r.estop.level = false; }, firmware::StopReason::EStop, -1);
    expect_hold_after([](PlaybackRig& r) { r.drive_fault = true; }, firmware::StopReason::DriveFault, 1);
    expect_hold_after([](PlaybackRig& r) { r.joint2_silent = true; }, firmware::StopReason::StaleJoint, 1);
    expect_hold_after([](PlaybackRig& r) { r.cycle->note_missed_deadline(); }, firmware::StopReason::MissedDeadline, -1);
}

// An overrun while the firmware waits for every joint's first sample (start-up, before anything is
// commanded) must not stop the playback that starts later: the VM board run stopped at row 1, cycle 0,
// on a flag set during jacobid-fw's start-up. An overrun once commands flow still stops it (above).
TEST(FirmwarePlayback, ADeadlineMissedBeforeThePlaybackStartsDoesNotStopIt) {
    PlaybackRig rig;
    rig.cycle->note_missed_deadline();  // the loop's start-up overrun, before the first tick
    rig.run(1 + 500 + 100);
    EXPECT_EQ(rig.cycle->player().phase(), firmware::PlaybackPhase::Playing) << firmware::to_string(rig.cycle->player().stop_reason());
    EXPECT_EQ(rig.cycle->counters().stop_cycles, 0u);
}

// Issue 36's acceptance: a table with a step beyond the limits never reaches a drive. The cycle refuses it
// in configure() (one line naming the table's line, the joint, the step and the limit), and a cycle that
// was refused sends nothing, however long it is stepped with the drives answering.
void expect_no_command_frame(void (*edit)(firmware::FirmwareConfig&), const std::string& message_start, const std::string& message_part) {
    PlaybackRig rig(edit);
    const std::string& table = rig.config.trajectory.file;
    EXPECT_EQ(rig.configured.rfind(table + message_start, 0), 0u) << rig.configured;
    EXPECT_NE(rig.configured.find(message_part), std::string::npos) << rig.configured;
    EXPECT_EQ(rig.configured.find('\n'), std::string::npos) << "one line: " << rig.configured;
    rig.run(1 + 500 + 3000);
    EXPECT_EQ(rig.frames_at_drives, 0u) << "no frame at all reached the drives";
    EXPECT_EQ(rig.cycle->counters().command_frames, 0u);
    EXPECT_EQ(rig.cycle->player().phase(), firmware::PlaybackPhase::Idle);
    EXPECT_TRUE(rig.log.records.empty());
}

TEST(FirmwarePlayback, AStepBeyondTheLimitsSendsNoCommandFrame) {
    // A 2 rad jump of joint 1 between lines 1001 and 1002, every row within the (widened) position limits
    // and the velocity column untouched (within its limit).
    expect_no_command_frame(
        [](firmware::FirmwareConfig& c) {
            for (std::size_t j = 0; j < 2; ++j) {
                c.trajectory.position_min[j] = -4.0;
                c.trajectory.position_max[j] = 4.0;
            }
            for (std::size_t r = 1000; r < c.trajectory.rows.size(); ++r) c.trajectory.rows[r].q[0] += 2.0;
        },
        ":1002: joint 1: the position steps 2 rad from line 1001, 2000 rad/s at 1000 Hz, beyond the velocity limit 3 rad/s "
        "(trajectory.joints[0].velocity, +1 %)",
        "");
}

TEST(FirmwarePlayback, AWrapWithoutARampSendsNoCommandFrame) {
    // Half of the 2 s period (0.2 -> 1.2 rad, at rest at both ends), repeat: 2: the next pass would start
    // with a 1 rad step in one cycle.
    expect_no_command_frame([](firmware::FirmwareConfig& c) { c.trajectory.rows.resize(1001); },
                            ":2: joint 1: the position steps -1 rad from line 1002, -1000 rad/s at 1000 Hz, beyond the velocity limit 3 rad/s",
                            "this is the wrap from the table's last row (line 1002) to its next pass (repeat: 2)");
}

TEST(FirmwarePlayback, CsvCommandLogWritesAHeaderAndOneLinePerRecord) {
    const std::string file = (test::scratch_directory() / "commands.csv").string();
    {
        firmware::CsvCommandLog log;
        ASSERT_EQ(log.open(file, 2), "");
        firmware::CommandRecord r;
        r.time_ns = 1'000'000'123;
        r.phase = firmware::PlaybackPhase::Stopped;
        r.reason = firmware::StopReason::FollowingError;
        r.row = 7;
        r.joints = 2;
        r.measured = {0.5, -0.25};
        r.position = {0.125, 1.5};
        r.velocity = {0.0, 2.0};
        r.torque = {3.0, -4.0};
        log.record(r);
        EXPECT_TRUE(log.flush());
        EXPECT_EQ(log.failures(), 0u);
    }
    std::ifstream in(file);
    std::string header, line;
    std::getline(in, header);
    std::getline(in, line);
    EXPECT_EQ(header, "t_ns,phase,stop_reason,row,q1,q_cmd1,qd_cmd1,tau_cmd1,q2,q_cmd2,qd_cmd2,tau_cmd2");
    EXPECT_EQ(line, "1000000123,stopped,following error,7,0.5,0.125,0,3,-0.25,1.5,2,-4");
    EXPECT_FALSE(std::getline(in, line));
}

TEST(FirmwarePlayback, ConfigNamesTheMissingLimitAndTheBadTableLine) {
    const std::string table = write_table();
    auto error_of = [](const std::string& extra) {
        try {
            test::chain_config(extra);
        } catch (const firmware::ConfigError& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    const std::string no_torque = "trajectory:\n  file: " + table + "\n  joints:\n    - {position: [-2, 2], velocity: 3, acceleration: 10, following_error: 0.01, kp: 10, kd: 1}\n"
                                  "    - {position: [-2, 2], velocity: 3, acceleration: 10, torque: 8, following_error: 0.01, kp: 10, kd: 1}\n";
    EXPECT_NE(error_of(no_torque).find("trajectory.joints[0].torque: missing (required)"), std::string::npos) << error_of(no_torque);
    const std::string one_joint = "trajectory:\n  file: " + table + "\n  joints:\n    - {position: [-2, 2], velocity: 3, acceleration: 10, torque: 8, following_error: 0.01, kp: 10, kd: 1}\n";
    EXPECT_NE(error_of(one_joint).find("trajectory.joints: must be a list of 2"), std::string::npos) << error_of(one_joint);
    const std::string bad = (test::scratch_directory() / "bad_table.csv").string();
    std::ofstream(bad) << "t,q1,q2,qd1,qd2\n0,0,0,0,0\n0.001,0,x,0,0\n";
    const std::string bad_table = "trajectory:\n  file: " + bad + "\n  joints:\n    - {position: [-2, 2], velocity: 3, acceleration: 10, torque: 8, following_error: 0.01, kp: 10, kd: 1}\n"
                                  "    - {position: [-2, 2], velocity: 3, acceleration: 10, torque: 8, following_error: 0.01, kp: 10, kd: 1}\n";
    EXPECT_EQ(error_of(bad_table), bad + ":3:3: column q2: 'x' is not a finite number");
    std::ofstream(bad) << "t,q1,q2,qd1,qd2\n0,0,0,0,0\n0.002,0,0,0,0\n";
    EXPECT_NE(error_of(bad_table).find(":3:1: t = 0.002 s, expected 0.001 s"), std::string::npos) << error_of(bad_table);
    const std::string device = "trajectory:\n  file: /dev/zero\n  joints:\n    - {position: [-2, 2], velocity: 3, acceleration: 10, torque: 8, following_error: 0.01, kp: 10, kd: 1}\n"
                               "    - {position: [-2, 2], velocity: 3, acceleration: 10, torque: 8, following_error: 0.01, kp: 10, kd: 1}\n";
    EXPECT_EQ(error_of(device), "/dev/zero: cannot read the trajectory table: not a regular file (a device, FIFO or socket)");
    // A row beyond a limit is refused at start-up by the cycle, naming the table, the joint and the row.
    firmware::FirmwareConfig c = test::chain_config(playback_yaml());
    c.trajectory.rows[10].q[1] = 2.5;
    test::TestBus bus;
    test::MemoryPublisher publisher;
    firmware::FirmwareCycle cycle(*bus.attach(), publisher, nullptr);
    EXPECT_EQ(cycle.configure(c), c.trajectory.file + ":12: joint 2: position 2.5 rad outside the limits [-2, 2] rad (trajectory.joints[1].position)");
}

}  // namespace
