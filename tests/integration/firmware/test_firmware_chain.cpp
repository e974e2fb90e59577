// SPDX-License-Identifier: MIT
// The whole chain: closed-loop 2R simulator -> MIT frames on the virtual CAN bus (CanPlayer, the core of
// `jacobid sim-can`) -> FirmwareCycle -> estimate datagrams -> the recorder of `jacobid record` -> CSV ->
// `jacobid identify`. The expected values are the simulator's truth (the paper's Table II).
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "firmware_chain_bench.hpp"
#include "firmware_test_support.hpp"
#include "identification_bars.hpp"
#include "jacobid/firmware/runtime.hpp"
#include "robot/planar2r_model.hpp"
#include "robot/robot_description.hpp"
#include "run_command.hpp"
#include "scratch_directory.hpp"
#include "sim/can_player.hpp"
#include "sim/command_follower.hpp"
#include "sim/simulator.hpp"
#include "stream/recorder.hpp"
#include "../stream/stream_test_support.hpp"

namespace {

using namespace jacobid;
using nlohmann::json;

std::string path(const std::string& name) { return (test::scratch_directory() / name).string(); }

struct ChainResult {
    std::uint64_t samples = 0;
    firmware::CycleCounters counters;
    std::size_t delay = 0;
    sim::CanPlayerCounters player;
};

// Runs `seconds` of the simulated robot through the chain; every datagram goes to `publish`.
// `pace` sleeps so that the datagrams leave at the given rate in wall time (0: as fast as possible).
ChainResult run_chain(double seconds, firmware::Publisher& publisher, double pace_hz = 0.0) {
    test::ChainBench bench(publisher, test::chain_config());
    sim::SimulationSettings settings;
    settings.duration = seconds;
    settings.seed = 7;
    bench.simulate(settings, pace_hz);
    ChainResult result;
    result.samples = bench.samples;
    result.counters = bench.cycle->counters();
    result.delay = bench.cycle->delay_samples();
    result.player = bench.player.counters();
    return result;
}

// Feeds the in-process recorder, exactly as `jacobid record` does with what it receives.
class RecorderPublisher final : public firmware::Publisher {
public:
    explicit RecorderPublisher(stream::Recorder& r) : recorder_(r) { buffer_.reserve(65536); }
    bool publish(Span<const std::uint8_t> d) noexcept override {
        buffer_.assign(d.data(), d.data() + d.size());
        recorder_.datagram(buffer_, d.size());
        return true;
    }

private:
    stream::Recorder& recorder_;
    std::vector<std::uint8_t> buffer_;
};

// `jacobid identify` (Jacobi, automatic windows) of a recorded 2R log, the figures printed for the docs;
// an empty object (and a failure) if the command fails.
json identify_recorded_2r(const std::string& log, const char* label) {
    std::ofstream(path("robot.yaml")) << "model: planar2r\nL1: 0.5\nfriction: {coulomb: smooth, alpha: 100}\n";
    const test::CommandResult id = test::run_command(std::string(JACOBID_EXECUTABLE) + " identify --robot " + path("robot.yaml") +
                                                     " --in " + log + " --method jacobi --format json --quiet");
    EXPECT_EQ(id.exit_code, 0) << id.err;
    if (id.exit_code != 0) return json::object({{"parameters", json::object()}});
    const json j = json::parse(id.out);
    std::printf("%s identification: ZZ1R %.4g ZZ2 %.4g MX2 %.4g FC1 %.4g FC2 %.4g, relative error norm %.4g\n", label,
                j["parameters"]["ZZ1R"]["value"].get<double>(), j["parameters"]["ZZ2"]["value"].get<double>(),
                j["parameters"]["MX2"]["value"].get<double>(), j["parameters"]["FC1"]["value"].get<double>(),
                j["parameters"]["FC2"]["value"].get<double>(), j["relative_error_norm"].get<double>());
    return j;
}

TEST(Chain, SimCanFirmwareRecordIdentifyWithinTheIssueAccuracy) {
    const std::string log = path("chain.csv");
    stream::Recorder recorder({log, stream::GapPolicy::Error, true, 32});
    RecorderPublisher publisher(recorder);
    const ChainResult r = run_chain(30.0, publisher);
    recorder.finish();

    EXPECT_EQ(r.samples, 30001u);
    EXPECT_EQ(r.player.send_failures, 0u);
    const auto& c = r.counters;
    EXPECT_EQ(c.datagrams_published, r.samples - r.delay);
    EXPECT_EQ(c.publish_failures + c.encode_failures, 0u);
    EXPECT_EQ(c.decode.decoded, 2 * r.samples);
    EXPECT_EQ(c.decode.frames, c.decode.decoded) << "no frame rejected on a clean bus";
    EXPECT_EQ(c.joints[0].stale_samples + c.joints[1].stale_samples, 0u);
    // 0 lost datagrams, every one a row, nothing the recorder would call a hole.
    EXPECT_EQ(recorder.received(), c.datagrams_published);
    EXPECT_EQ(recorder.tracker().lost_count(), 0u);
    EXPECT_EQ(recorder.malformed(), 0u);
    EXPECT_EQ(recorder.rows_written(), c.datagrams_published);
    EXPECT_TRUE(recorder.holes().empty());

    const json j = identify_recorded_2r(log, "chain");
    test::expect_table2_bars(j);
    EXPECT_TRUE(j["settings"]["bandwidth_estimated"].get<bool>());
}

// A 10 s period of five harmonics for the 2R (at rest at t = 0), written at 1 kHz for jacobid-fw to play.
std::string write_excitation_table() {
    const std::string file = path("loop_traj.csv");
    std::ofstream out(file);
    out.precision(17);
    out << "t,q1,q2,qd1,qd2\n";
    const double w = 2.0 * M_PI / 10.0;
    // q_j = c_j + sum_l a_jl (1 - cos(l w t)), l = 1..5
    const double c[2] = {0.3, -0.4};
    const double a[2][5] = {{0.6, 0.2, -0.25, 0.1, 0.08}, {0.5, 0.4, 0.3, -0.15, 0.1}};
    for (int k = 0; k <= 10000; ++k) {
        const double t = k * 1e-3;
        double q[2], qd[2];
        for (int j = 0; j < 2; ++j) {
            q[j] = c[j];
            qd[j] = 0.0;
            for (int l = 1; l <= 5; ++l) {
                q[j] += a[j][l - 1] * (1.0 - std::cos(l * w * t));
                qd[j] += a[j][l - 1] * l * w * std::sin(l * w * t);
            }
        }
        out << t << ',' << q[0] << ',' << q[1] << ',' << qd[0] << ',' << qd[1] << '\n';
    }
    return file;
}

// The loop of issue 17 on the virtual bus: FirmwareCycle plays the table (fw.yaml trajectory:, 3 passes),
// the closed-loop 2R simulator follows its MIT command frames (sim::CommandFollower, the core of
// `sim-can --follow`) and answers with telemetry, the estimates go to the recorder, and `jacobid identify`
// gets the Table II truth from what the robot did while playing.
TEST(Chain, PlaybackLoopSimulatedRobotFollowsAndIdentifies) {
    const std::string log = path("loop.csv");
    stream::Recorder recorder({log, stream::GapPolicy::Error, true, 32});
    RecorderPublisher publisher(recorder);
    const firmware::FirmwareConfig config = test::chain_config(
        "trajectory:\n  file: " + write_excitation_table() + "\n  ramp_time: 1\n  repeat: 3\n  joints:\n"
        "    - {position: [-3, 3], velocity: 5, acceleration: 20, torque: 120, following_error: 0.2, kp: 40, kd: 1}\n"
        "    - {position: [-3, 3], velocity: 5, acceleration: 20, torque: 8, following_error: 0.2, kp: 10, kd: 0.5}\n");
    test::ChainBench bench(publisher, config);
    sim::CommandFollower follower(*bench.sim_end, test::profiles_of(config), {0.0, 0.0});
    sim::SimulationSettings settings;
    settings.duration = 1.0 + 3 * 10.0 + 0.5;
    settings.reference = [&follower](double t, sim::ReferenceSample& out) { follower.reference(t, out); };
    settings.reference_start = {0.0, 0.0};
    bench.simulate(settings);
    recorder.finish();
    const auto& cycle = bench.cycle;
    const firmware::TrajectoryPlayer& p = cycle->player();
    EXPECT_EQ(p.phase(), firmware::PlaybackPhase::Finished) << firmware::to_string(p.stop_reason()) << " joint " << p.stop_joint() + 1 << " at cycle " << p.cycles() << ", row " << p.row() << ", command " << p.commands()[1].position;
    EXPECT_EQ(cycle->counters().command_failures, 0u);
    // The simulated drives read every command frame but the last cycle's two (sent after the last control instant).
    EXPECT_EQ(follower.counters().commands + 2, cycle->counters().command_frames);
    EXPECT_EQ(follower.counters().rejected, 0u);
    EXPECT_GE(follower.counters().joint_commands[1], 1000u + 3u * 10000u);

    test::expect_table2_bars(identify_recorded_2r(log, "playback loop"));
}

// The same chain over a real UDP socket into the `jacobid record` executable, paced at 1 kHz wall time
// (3 s of robot), so the UdpPublisher and the recorder's socket path are part of it: 0 datagrams lost.
TEST(Chain, UdpPublisherIntoJacobidRecordAtOneKilohertz) {
    const std::string csv = path("udp.csv"), summary = path("udp.summary.json"), err = path("udp.err");
    // Port 0: the recorder picks a free one and says which in its "listening on" line; the datagrams are
    // sent once that line is there (waited for, with a timeout), not after a pause.
    test::Recorder recorder({"record", "--quiet", "--udp", "127.0.0.1:0", "-o", csv, "--summary", summary, "--idle-timeout", "1.5"}, err);
    const int port = recorder.wait_for_port();
    firmware::UdpPublisher udp;
    ASSERT_EQ(udp.open("127.0.0.1", static_cast<std::uint16_t>(port)), "");
    const ChainResult r = run_chain(3.0, udp, 1000.0);
    const int exit_code = recorder.wait(30.0);
    EXPECT_EQ(exit_code, 0) << recorder.err();
    EXPECT_EQ(r.counters.publish_failures, 0u);
    std::ifstream in(summary);
    const json s = json::parse(in);
    EXPECT_EQ(s["datagrams"]["received"].get<std::uint64_t>(), r.counters.datagrams_published) << s.dump(2);
    EXPECT_EQ(s["rows"]["written"].get<std::uint64_t>(), r.counters.datagrams_published) << s.dump(2);
    EXPECT_EQ(s["datagrams"]["lost"].get<std::uint64_t>(), 0u) << s.dump(2);
}

}  // namespace
