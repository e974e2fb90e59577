// SPDX-License-Identifier: MIT
// The contact monitor in the firmware cycle (fw.yaml `monitor:`, docs/firmware.md "Contact monitor"; issue
// 40) end to end on the virtual bus: the closed-loop 2R simulator with a simulated external torque pulse ->
// MIT telemetry -> FirmwareCycle with the monitor -> version-2 datagrams -> the recorder of `jacobid record`
// -> CSV. The references are the simulator's: the pulse it applied (its time and size), not the monitor's output.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "core/errors.hpp"
#include "firmware_chain_bench.hpp"
#include "monitor_test_support.hpp"
#include "sim/command_follower.hpp"
#include "stream/recorder.hpp"

namespace {

using namespace jacobid;

constexpr double kOnset = 5.0;      // s: the pulse on joint 1 starts ...
constexpr double kDuration = 0.3;   // s: ... lasts ...
constexpr double kPulse = 15.0;     // N.m: ... and pushes this hard
constexpr std::int64_t kOnsetNs = 5'000'000'000;

std::string path(const std::string& name) { return (test::scratch_directory() / name).string(); }

// A robot at work, not an identification run: random moves of 2-3 s within 4 rad/s^2. (The identification's
// fast moves, 0.6-1.6 s, put 38 N.m of estimate error on joint 1 through the differentiators' lag at fw.yaml's
// 50 ms velocity window: docs/firmware.md, "Contact monitor".)
sim::MoveSettings working_moves() {
    sim::MoveSettings m;
    m.min_duration = 2.0;
    m.max_duration = 3.0;
    m.acceleration_limit = {4.0};
    return m;
}

sim::SimulationSettings pulse_settings(double duration, double onset, std::uint64_t seed = 7) {
    sim::SimulationSettings s;
    s.duration = duration;
    s.seed = seed;
    s.moves = working_moves();
    s.external_torque = [onset](double t, Eigen::VectorXd& out) {
        out.setZero(2);
        if (t >= onset && t < onset + kDuration) out[0] = kPulse;
    };
    return s;
}

// Thresholds from contact-free runs, as `jacobid monitor calibrate --false-alarm-rate 0 --margin 0.5` sets
// them (docs/monitor.md), on the firmware's own estimates: `run` simulates one contact-free run on the bench.
template <typename Run>
test::Thresholds calibrate(const std::string& tag, const std::string& extra, int runs, Run run) {
    test::ThresholdCalibration calibration;
    for (int i = 0; i < runs; ++i) {
        test::MemoryPublisher publisher;
        test::ChainBench bench(publisher, test::monitored_chain_config(tag, "flag", extra));
        bench.noise_seed = 100 + static_cast<std::uint64_t>(i);  // not the tested runs' noise (seed 8)
        bench.after_step = [&](const sim::SimulatedSample&, std::int64_t) { calibration.add(bench.cycle->monitor()); };
        run(bench, i);
    }
    const test::Thresholds t = calibration.thresholds(0.5);
    std::printf("monitor: thresholds from %d contact-free run(s): moving %.3f %.3f N.m, standing beyond the band %.3f %.3f N.m\n", runs,
                t.moving[0], t.moving[1], t.standing[0], t.standing[1]);
    return t;
}

// Random moves of seeds 11, 12, 13, 10 s each (the pulse runs use seed 7).
test::Thresholds calibrate_random_moves() {
    return calibrate("calibration", "", 3, [](test::ChainBench& bench, int i) {
        sim::SimulationSettings s;
        s.duration = 10.0;
        s.seed = 11 + static_cast<std::uint64_t>(i);
        s.moves = working_moves();
        bench.simulate(s);
    });
}

// Columns of a recorded CSV by name.
std::map<std::string, std::vector<double>> read_columns(const std::string& file) {
    std::ifstream in(file);
    std::string line;
    std::getline(in, line);
    std::vector<std::string> names;
    std::stringstream header(line);
    for (std::string cell; std::getline(header, cell, ',');) names.push_back(cell);
    std::map<std::string, std::vector<double>> columns;
    while (std::getline(in, line)) {
        std::stringstream row(line);
        std::size_t i = 0;
        for (std::string cell; std::getline(row, cell, ',') && i < names.size(); ++i) columns[names[i]].push_back(std::stod(cell));
    }
    return columns;
}

// What the cycle did in the cycle that first confirmed a contact.
struct FirstContact {
    std::int64_t cycle_ns = -1;  // the cycle's time
    std::int64_t row_ns = -1;    // the instant the row (and its estimate) describes
    bool enable_line_low = false, stopped_by_contact = false;
    std::uint64_t stop_cycles = 0;
    firmware::PlaybackPhase phase = firmware::PlaybackPhase::Idle;
    firmware::StopReason reason = firmware::StopReason::None;
    std::string what;  // for messages: the joints over their thresholds and the estimates
};

void watch_first_contact(test::ChainBench& bench, FirstContact& first) {
    bench.after_step = [&bench, &first](const sim::SimulatedSample&, std::int64_t now) {
        if (first.cycle_ns >= 0 || bench.cycle->counters().contact_rows == 0) return;
        first.cycle_ns = now;
        first.row_ns = bench.cycle->last_datagram().timestamp_ns;
        first.enable_line_low = !bench.enable.level;  // enable_active_low: false, so low = drives off
        first.stopped_by_contact = bench.safety.stopped() && bench.safety.stop_cause() == hal::StopCause::Contact;
        first.stop_cycles = bench.cycle->counters().stop_cycles;
        first.phase = bench.cycle->player().phase();
        first.reason = bench.cycle->player().stop_reason();
        const firmware::MonitorRow& row = bench.cycle->monitor().last();
        const auto& d = bench.cycle->last_datagram();
        first.what = "over mask " + std::to_string(row.over) + ", tau_ext " + std::to_string(row.external[0]) + " " + std::to_string(row.external[1]) +
                     ", qd^ " + std::to_string(d.joints[0].qd_hat) + " " + std::to_string(d.joints[1].qd_hat);
    };
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? NAN : v[v.size() / 2];
}

TEST(FirmwareMonitor, ExternalTorquePulseDropsTheEnableInItsCycleAndIsRecorded) {
    const std::string log = path("monitor_pulse.csv");
    stream::Recorder recorder({log, stream::GapPolicy::Mark, false, 32});
    test::MemoryPublisher publisher;
    std::vector<std::uint8_t> bytes;
    publisher.on_datagram = [&](Span<const std::uint8_t> d) {
        bytes.assign(d.data(), d.data() + d.size());
        recorder.datagram(bytes, d.size());
    };
    test::ChainBench bench(publisher, test::monitored_chain_config("pulse", "stop", "", calibrate_random_moves()));
    FirstContact first;
    watch_first_contact(bench, first);
    bench.simulate(pulse_settings(7.0, kOnset));
    recorder.finish();

    const double delay = static_cast<double>(bench.cycle->delay_samples()) * 1e-3;
    ASSERT_GE(first.cycle_ns, 0) << "the 15 N.m pulse was not detected";
    // Nothing before the pulse: the first contact row describes an instant at or after its onset.
    EXPECT_GE(first.row_ns, kOnsetNs) << first.what;
    // Known one bank delay after the row's instant, plus the observer's rise to the threshold (ln(15/12)/K = 2 ms).
    const double latency = static_cast<double>(first.cycle_ns - kOnsetNs) * 1e-9;
    EXPECT_LE(latency, delay + 0.02) << "bank delay " << delay << " s";
    std::printf("monitor: pulse of %g N.m detected %.1f ms after its onset (bank delay %.0f ms)\n", kPulse, latency * 1e3, delay * 1e3);
    // The action in the same cycle: the drive enable dropped, the latch says why.
    EXPECT_TRUE(first.enable_line_low);
    EXPECT_TRUE(first.stopped_by_contact);
    EXPECT_EQ(bench.cycle->contact_joint(), 0);
    EXPECT_EQ(bench.cycle->counters().encode_failures, 0u);

    // The recorded stream: version 2, tau_ext per joint, the contact flags.
    EXPECT_EQ(publisher.last.version, stream::kDatagramVersionMonitor);
    auto c = read_columns(log);
    ASSERT_EQ(c.count("tau_ext1_hat"), 1u);
    ASSERT_EQ(c.count("tau_ext2_hat"), 1u);
    std::vector<double> held, before;
    std::size_t contact_rows = 0;
    double first_flagged = -1.0;
    for (std::size_t i = 0; i < c["t"].size(); ++i) {
        const double t = c["t"][i];
        const auto stream_flags = static_cast<std::uint32_t>(c["stream_flags"][i]);
        if (stream_flags & stream::kStreamContact) {
            ++contact_rows;
            if (first_flagged < 0.0) first_flagged = t;
            EXPECT_NE(static_cast<std::uint32_t>(c["flags1"][i]) & stream::kJointContact, 0u) << "t = " << t;
        }
        // Five observer time constants after the onset, to the pulse's end: the level the pulse holds.
        if (t >= kOnset + 0.05 && t < kOnset + kDuration) held.push_back(c["tau_ext1_hat"][i]);
        if (t >= 1.0 && t < kOnset) before.push_back(std::abs(c["tau_ext1_hat"][i]));
    }
    EXPECT_EQ(contact_rows, bench.cycle->counters().contact_rows);
    EXPECT_NEAR(first_flagged, kOnset, 0.02);
    EXPECT_NEAR(median(held), kPulse, 0.1 * kPulse);
    EXPECT_LT(*std::max_element(before.begin(), before.end()), 3.0);
    std::printf("monitor: level %.2f N.m during the %g N.m pulse; largest |tau_ext1| before it %.3f N.m\n", median(held), kPulse,
                *std::max_element(before.begin(), before.end()));
}

// With playback, the contact's stop goes out through the profile's command path in the cycle that confirms
// it: the player is stopped with reason `contact` and that cycle already sent the hold.
TEST(FirmwareMonitor, ContactStopsThePlaybackWithTheHoldInTheSameCycle) {
    std::ofstream table(path("monitor_traj.csv"));
    table << "t,q1,q2,qd1,qd2\n";
    // A slow cosine on both joints from rest (period 8 s), 20 s at 1 kHz.
    for (int k = 0; k <= 20000; ++k) {
        const double t = k * 1e-3, w = 2.0 * M_PI / 8.0;
        table << t << ',' << 0.5 * (1.0 - std::cos(w * t)) << ',' << -0.4 * (1.0 - std::cos(w * t)) << ',' << 0.5 * w * std::sin(w * t) << ','
              << -0.4 * w * std::sin(w * t) << '\n';
    }
    table.close();
    const std::string playback =
        "trajectory:\n  file: monitor_traj.csv\n  ramp_time: 1\n  joints:\n"
        "    - {position: [-3, 3], velocity: 5, acceleration: 20, torque: 120, following_error: 0.2, kp: 40, kd: 1}\n"
        "    - {position: [-3, 3], velocity: 5, acceleration: 20, torque: 8, following_error: 0.2, kp: 10, kd: 0.5}\n";
    // The robot playing the table without contact: the run the thresholds come from.
    const auto play = [](test::ChainBench& bench, const firmware::FirmwareConfig& config, sim::SimulationSettings settings) {
        sim::CommandFollower follower(*bench.sim_end, test::profiles_of(config), {0.0, 0.0});
        settings.reference = [&follower](double t, sim::ReferenceSample& out) { follower.reference(t, out); };
        settings.reference_start = {0.0, 0.0};
        bench.simulate(settings);
    };
    const test::Thresholds thresholds = calibrate("play_calibration", playback, 1, [&](test::ChainBench& bench, int) {
        sim::SimulationSettings s;
        s.duration = 8.0;
        play(bench, test::monitored_chain_config("play_calibration", "flag", playback), s);
    });
    const firmware::FirmwareConfig config = test::monitored_chain_config("play", "stop", playback, thresholds);
    test::MemoryPublisher publisher;
    test::ChainBench bench(publisher, config);
    FirstContact first;
    watch_first_contact(bench, first);
    play(bench, config, pulse_settings(8.0, 6.0));

    ASSERT_GE(first.cycle_ns, 0) << "the pulse was not detected";
    EXPECT_GE(first.row_ns, 6'000'000'000) << "a contact before the pulse: " << first.what;
    EXPECT_EQ(first.phase, firmware::PlaybackPhase::Stopped);
    EXPECT_EQ(first.reason, firmware::StopReason::Contact);
    EXPECT_EQ(first.stop_cycles, 1u) << "the hold is sent in the cycle that confirms the contact";
    EXPECT_EQ(bench.cycle->player().stop_joint(), 0);
    EXPECT_TRUE(first.enable_line_low);
}

// monitor.stream: false keeps the stream at version 1 (receivers built before version 2 read it); the
// detection and its action are unchanged.
TEST(FirmwareMonitor, StreamFalseKeepsVersionOneAndStillActs) {
    test::MemoryPublisher publisher;
    firmware::FirmwareConfig config = test::monitored_chain_config("v1", "stop");
    config.monitor.stream = false;
    test::ChainBench bench(publisher, config);
    bench.simulate(pulse_settings(5.6, kOnset));
    EXPECT_EQ(publisher.last_status, stream::DatagramStatus::Ok);
    EXPECT_EQ(publisher.last.version, stream::kDatagramVersion);
    EXPECT_EQ(bench.cycle->last_encoded().size(), stream::datagram_size(2));
    EXPECT_GT(bench.cycle->counters().contact_rows, 0u);
    EXPECT_TRUE(bench.safety.stopped());
    EXPECT_EQ(bench.safety.stop_cause(), hal::StopCause::Contact);
}

// action: flag only flags: the drives stay enabled.
TEST(FirmwareMonitor, ActionFlagOnlyFlags) {
    test::MemoryPublisher publisher;
    test::ChainBench bench(publisher, test::monitored_chain_config("flag", "flag"));
    std::uint64_t flagged = 0;
    publisher.on_datagram = [&](Span<const std::uint8_t>) { flagged += (publisher.last.flags & stream::kStreamContact) != 0; };
    bench.simulate(pulse_settings(5.6, kOnset));
    EXPECT_GT(flagged, 0u);
    EXPECT_EQ(flagged, bench.cycle->counters().contact_rows);
    EXPECT_EQ(bench.cycle->counters().contact_stops, 0u);
    EXPECT_FALSE(bench.safety.stopped());
    EXPECT_TRUE(bench.enable.level);
}

TEST(FirmwareMonitorConfig, BandMarginOfTheMonitorFileWidensTheControllersStandstillBand) {
    // planar2r_mdh_yaml: FC1 = 0.431, FC2 = 0.1268 N.m; band_margin 0.2: the arm at rest holds 1.2 x FC.
    test::Thresholds t;
    t.band_margin = 0.2;
    const firmware::FirmwareConfig c = test::monitored_chain_config("band_margin", "flag", "", t);
    firmware::CycleMonitor monitor;
    ASSERT_EQ(monitor.configure(c.monitor.model, 2, c.sample_period()), "");
    const firmware::CycleMonitor::Joints zero = firmware::CycleMonitor::Joints::Zero();
    for (int k = 0; k < 200; ++k) monitor.step(zero, zero, zero, true, true);  // the plane is horizontal: no gravity torque
    ASSERT_TRUE(monitor.estimate().standing[0] && monitor.estimate().standing[1]);
    EXPECT_NEAR(monitor.estimate().band[0], 1.2 * 0.431, 1e-12);
    EXPECT_NEAR(monitor.estimate().band[1], 1.2 * 0.1268, 1e-12);
}

TEST(FirmwareMonitorConfig, BadSectionsAndFilesAreOneLineNamingTheKeyOrFile) {
    const auto parse_error = [](const std::string& monitor) {
        try {
            firmware::parse_firmware_config(test::chain_config_yaml() + monitor, "fw.yaml");
        } catch (const firmware::ConfigError& e) {
            return std::string(e.what());
        }
        return std::string("(accepted)");
    };
    EXPECT_NE(parse_error("monitor: {thresholds: m.yaml}\n").find("monitor.robot"), std::string::npos) << parse_error("monitor: {thresholds: m.yaml}\n");
    EXPECT_NE(parse_error("monitor: {robot: r.yaml, thresholds: m.yaml, action: halt}\n").find("monitor.action"), std::string::npos);
    EXPECT_NE(parse_error("monitor: {robot: r.yaml, thresholds: m.yaml, gain: 3}\n").find("monitor.gain"), std::string::npos);
    EXPECT_NE(parse_error("monitor: {robot: r.yaml, thresholds: m.yaml, stream: {log: x.bin}}\n").find("monitor"), std::string::npos);

    // A monitor YAML for three joints on fw.yaml's two: the loader names the file and the key.
    const std::string dir = test::scratch_directory().string() + "/";
    std::ofstream(dir + "three_robot.yaml") << test::planar2r_mdh_yaml();
    std::ofstream(dir + "three_monitor.yaml") << "joints: [{moving: 1, standing: 1}, {moving: 1, standing: 1}, {moving: 1, standing: 1}]\n";
    firmware::FirmwareConfig c =
        firmware::parse_firmware_config(test::chain_config_yaml() + "monitor: {robot: three_robot.yaml, thresholds: three_monitor.yaml}\n", dir + "fw.yaml");
    try {
        monitor::load_firmware_monitor(c);
        ADD_FAILURE() << "accepted a monitor YAML for 3 joints";
    } catch (const InputError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("three_monitor.yaml"), std::string::npos) << what;
        EXPECT_NE(what.find("joints"), std::string::npos) << what;
        EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
    // A residual estimator: the controller runs the observer.
    std::ofstream(dir + "res_monitor.yaml") << "estimator: {type: residual}\njoints: [{moving: 1, standing: 1}, {moving: 1, standing: 1}]\n";
    c.monitor.thresholds = dir + "res_monitor.yaml";
    try {
        monitor::load_firmware_monitor(c);
        ADD_FAILURE() << "accepted a residual estimator";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("estimator.type"), std::string::npos) << e.what();
    }
}

}  // namespace
