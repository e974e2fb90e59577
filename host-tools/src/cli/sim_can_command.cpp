// SPDX-License-Identifier: MIT
// jacobid sim-can: the closed-loop simulator playing the motor drivers on a CAN interface. Every output
// sample (1 kHz by default) becomes one frame per joint (two for ODrive) in the chosen profile, sent at
// the sample's wall-clock time, so that sim-can -> CAN -> jacobid-fw -> UDP -> record -> identify runs
// as on a robot. The core is sim::CanPlayer (any CanTransport); this command only opens SocketCAN.
// With a SYNC id (--sync-id, or can.sync_id of the firmware config) the drives answer the firmware's
// CANopen SYNC instead of their own clock: one sample per SYNC, as synchronous TPDOs do.
#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include <poll.h>

#include <cmath>
#include <ctime>
#include <memory>

#include "cli/command.hpp"
#include "options/option_checks.hpp"
#include "options/simulation_options.hpp"
#include "options/output_file.hpp"
#include "options/robot_files.hpp"
#include "robot/robot_description.hpp"
#include "robot/simulated_parameters.hpp"
#include "io/candump_writer.hpp"
#include "sim/can_player.hpp"
#include "sim/closed_loop.hpp"
#include "sim/command_follower.hpp"
#include "sim/simulator.hpp"

#if JACOBID_WITH_FIRMWARE
#include "jacobid/fwconfig/firmware_config_yaml.hpp"
#include "jacobid/hal/socketcan_transport.hpp"
#endif

namespace jacobid::cli {
namespace {

struct SimCanOptions {
    std::string robot;
    std::string profile = "mit";
    std::string config;
    std::string iface;
    std::string candump;
    sim::SimulationSettings settings;
    std::vector<double> torque_noise{0.05, 0.01};
    std::uint64_t noise_seed = 2;
    int sync_id = -1;           // -1: pace by the clock; else answer each SYNC frame with this id
    double sync_timeout = 1.0;  // s without a SYNC (after the first) that end the run with an error
    bool quiet = false;
    bool follow = false;        // the reference from the controller's command frames (sim/command_follower.hpp)
};

#if JACOBID_WITH_FIRMWARE
std::int64_t monotonic_ns() {
    timespec ts{};
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

void report_sent(const sim::CanPlayer& player) {
    const auto& c = player.counters();
    fmt::print(stderr, "sim-can: {} samples, {} frames sent, {} refused by the transport{}\n", c.samples, c.frames_sent, c.send_failures,
               c.send_failures ? fmt::format(" (last: {})", hal::describe(player.last_error())) : std::string());
}

// Blocks until a SYNC frame (the only frames the socket's filter lets through) arrives; `timeout_s`
// without one is an error that names the bus and the id.
// Following commands, the other frames read meanwhile go to `follower`.
void wait_for_sync(hal::SocketCanTransport& can, const SimCanOptions& o, double timeout_s, sim::CommandFollower* follower) {
    hal::CanFrame frame;
    for (;;) {
        const hal::CanStatus s = can.receive(frame);
        if (s == hal::CanStatus::Ok) {
            if (!frame.extended() && frame.id == static_cast<std::uint32_t>(o.sync_id)) return;
            if (follower) follower->take(frame);
            continue;
        }
        if (s != hal::CanStatus::Empty) throw InputError(fmt::format("--iface {}: {} (errno {})", o.iface, hal::describe(s), can.last_errno()));
        pollfd p{can.native_handle(), POLLIN, 0};
        const int ready = ::poll(&p, 1, static_cast<int>(timeout_s * 1e3));
        if (ready == 0) {
            throw InputError(fmt::format("--iface {}: no SYNC frame (id 0x{:03X}) for {} s: is jacobid-fw running with can.sync_id: 0x{:03X}?",
                                         o.iface, o.sync_id, timeout_s, o.sync_id));
        }
    }
}

void run(SimCanOptions o) {
    const robot::RobotDescription robot = o.robot.empty() ? robot::default_planar2r_description() : robot::load_robot_description(o.robot);
    std::vector<NamedPath> inputs = robot_files("--robot", o.robot, robot);
    inputs.push_back({"--config", o.config});
    check_outputs({{"--candump", o.candump}}, inputs);
    const auto model = robot::make_robot_model(robot);
    const auto n = static_cast<std::size_t>(model->joint_count());

    // Joint encodings: the firmware's own config when given (both sides then agree by construction),
    // otherwise the profile defaults the firmware also applies to `{profile: <name>}` joints.
    std::vector<hal::ProfileConfig> joints;
    if (!o.config.empty()) {
        firmware::FirmwareConfig fw;
        try {
            fw = firmware::load_firmware_config(o.config);
        } catch (const firmware::ConfigError& e) {
            throw InputError(fmt::format("--config {}", e.what()));
        }
        if (fw.joints.size() != n) {
            throw InputError(fmt::format("--config {}: {} joints, but the robot has {}", o.config, fw.joints.size(), n));
        }
        for (const auto& j : fw.joints) joints.push_back(j.decoder);
        if (o.sync_id < 0) o.sync_id = fw.sync_id;
    } else {
        for (std::size_t j = 0; j < n; ++j) {
            hal::ProfileConfig c;
            if (!firmware::default_profile_config(o.profile, j, c)) throw InputError(fmt::format("--profile {}: not a device profile", o.profile));
            joints.push_back(c);
        }
    }
    if (o.torque_noise.size() == 1) o.torque_noise.assign(n, o.torque_noise[0]);
    if (o.torque_noise.size() != n) throw InputError(fmt::format("--torque-noise: expected 1 or {} values, got {}", n, o.torque_noise.size()));
    sim::validate(o.settings);
    // A sample: one candump -L line (about 45 bytes) per joint.
    refuse_oversized_simulation(o.settings, 45.0 * static_cast<double>(n));

    const Eigen::VectorXd x = robot::simulated_parameters(robot, *model);
    sim::MeasurementSettings ms;
    ms.encoder_counts_per_rev = 0.0;  // the profile's position code is the quantization
    ms.torque_noise = o.torque_noise;
    ms.seed = o.noise_seed;
    sim::MeasurementModel measurement(ms);
    const double period_ns = 1e9 / o.settings.output_rate;
    std::uint64_t k = 0;
    if (o.follow && !o.candump.empty()) throw InputError("--follow with --candump: a capture file sends no commands to follow (use --iface)");
    if (!o.candump.empty()) {
        // A capture file instead of a bus: simulated time stamps, no pacing (as fast as it computes).
        io::CandumpWriter writer(o.candump, "can0");
        sim::CanPlayer player(writer, joints);
        constexpr std::int64_t kEpoch = 1'700'000'000'000'000'000;  // an arbitrary, realistic capture start
        sim::simulate(*model, x, robot.joints, o.settings, measurement, [&](const sim::SimulatedSample& s) {
            writer.set_time_ns(kEpoch + static_cast<std::int64_t>(std::llround(static_cast<double>(k++) * period_ns)));
            player.send(s.q.data(), s.qd.data(), s.tau_measured.data());
        });
        writer.close();
        if (!o.quiet) fmt::print(stderr, "sim-can: {} samples, {} frames written to {}\n", player.counters().samples, player.counters().frames_sent, o.candump);
        if (player.counters().send_failures) throw InputError(fmt::format("{}: {} frames could not be written", o.candump, player.counters().send_failures));
        return;
    }
    hal::SocketCanTransport can;
    hal::SocketCanConfig sc;
    sc.interface = o.iface.c_str();
    // Only the SYNC frames (if any): the other drives' frames would just fill the receive queue. Following
    // commands, every frame is read (the joints' decoders tell commands from the rest).
    const hal::CanFilter sync_filter = hal::exact_filter(o.sync_id < 0 ? 0u : static_cast<std::uint32_t>(o.sync_id));
    if (o.sync_id >= 0 && !o.follow) sc.filters = Span<const hal::CanFilter>(&sync_filter, 1);
    if (const hal::CanStatus s = can.open(sc); s != hal::CanStatus::Ok) {
        throw InputError(fmt::format("--iface {}: {} (errno {}); the in-process chain test runs the same simulator on the virtual bus",
                                     o.iface, hal::describe(s), can.last_errno()));
    }
    sim::CanPlayer player(can, joints);
    std::unique_ptr<sim::CommandFollower> follower;
    if (o.follow) {
        const Eigen::VectorXd q0 = sim::start_configuration(robot.joints);
        follower = std::make_unique<sim::CommandFollower>(can, joints, std::vector<double>(q0.data(), q0.data() + q0.size()));
        o.settings.reference = [&follower](double t, sim::ReferenceSample& out) { follower->reference(t, out); };
        o.settings.reference_start.assign(q0.data(), q0.data() + q0.size());
    }
    auto report = [&] {
        report_sent(player);
        if (follower) {
            const sim::CommandFollowerCounters& c = follower->counters();
            fmt::print(stderr, "sim-can: followed {} command frames ({} rejected) of {} read\n", c.commands, c.rejected, c.frames);
        }
    };
    const std::int64_t start = monotonic_ns() + 100'000'000;  // first frame 100 ms from now
    if (!o.quiet) {
        fmt::print(stderr, "sim-can: {} joints on {} ({}), {} s at {} Hz, {}\n", n, o.iface, o.config.empty() ? o.profile : o.config,
                   o.settings.duration, o.settings.output_rate,
                   o.sync_id < 0 ? std::string("paced by the clock") : fmt::format("one sample per SYNC (id 0x{:03X})", o.sync_id));
    }
    if (o.sync_id >= 0) {
        // The firmware may start after us: the first SYNC gets a long wait, the others sync_timeout.
        constexpr double kFirstSyncTimeout = 30.0;
        sim::simulate(*model, x, robot.joints, o.settings, measurement, [&](const sim::SimulatedSample& s) {
            wait_for_sync(can, o, k == 0 ? kFirstSyncTimeout : o.sync_timeout, follower.get());
            player.send(s.q.data(), s.qd.data(), s.tau_measured.data());
            ++k;
        });
        report();
        return;
    }
    sim::simulate(*model, x, robot.joints, o.settings, measurement, [&](const sim::SimulatedSample& s) {
        const std::int64_t due = start + static_cast<std::int64_t>(std::llround(static_cast<double>(k) * period_ns));
        const timespec ts{static_cast<time_t>(due / 1'000'000'000), static_cast<long>(due % 1'000'000'000)};
        while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) != 0) {
        }
        player.send(s.q.data(), s.qd.data(), s.tau_measured.data());
        ++k;
    });
    report();
}
#else
void run(const SimCanOptions&) { throw InputError("sim-can: this jacobid was built without the HAL/firmware (JACOBID_BUILD_HAL=OFF)"); }
#endif

// The profiles a firmware config can name (hal/profile_registry.hpp); sim-can offers the same.
std::vector<std::string> profile_names() {
#if JACOBID_WITH_FIRMWARE
    return firmware::firmware_profile_names();
#else
    return {};  // sim-can needs the HAL and the firmware config (see run())
#endif
}

}  // namespace

void add_sim_can_command(CLI::App& app) {
    auto o = std::make_shared<SimCanOptions>();
    CLI::App* cmd = app.add_subcommand("sim-can", "play the closed-loop robot simulator's motor drivers on a CAN interface (SocketCAN)");
    cmd->add_option("--robot", o->robot, "robot description (YAML); default: planar2r, L1 0.5 m, smoothed Coulomb friction")->check(file_path());
    cmd->add_option("--profile", o->profile, "device profile of every joint, with the firmware's defaults for it (docs/firmware.md)")
        ->check(CLI::IsMember(profile_names()))
        ->capture_default_str();
    cmd->add_option("--config", o->config, "take the joints' profiles, ids, ranges and gear ratios from this jacobid-fw config (overrides --profile)")->check(file_path());
    auto* iface = cmd->add_option("--iface", o->iface, "CAN interface, e.g. vcan0 or can0");
    auto* candump = cmd->add_option("--candump", o->candump,
                                    "write the frames to this candump -L capture (simulated time stamps) instead of a CAN interface")->check(file_path());
    iface->excludes(candump);
    cmd->callback([o, iface, candump] {
        if (iface->count() + candump->count() != 1) throw InputError("sim-can: give exactly one of --iface and --candump");
        run(*o);
    });
    cmd->add_option("--duration", o->settings.duration, "simulated (and wall-clock) time in s")->check(positive_number())->capture_default_str();
    cmd->add_option("--rate", o->settings.output_rate, "frames per joint per second (Hz)")->check(positive_number())->capture_default_str();
    cmd->add_option("--seed", o->settings.seed, "seed of the random moves")->check(whole_number_from(0))->capture_default_str();
    cmd->add_option("--substeps", o->settings.substeps,
                    "RK4 steps of the simulated robot per control period (fewer: less CPU per frame, e.g. on a small board, for a coarser "
                    "integration)")
        ->check(whole_number_in(1, 1000))
        ->capture_default_str();
    add_torque_noise_option(cmd, o->torque_noise);
    add_noise_seed_option(cmd, o->noise_seed);
    cmd->add_option("--sync-id", o->sync_id,
                    "answer each CANopen SYNC frame with this standard id with the next sample instead of pacing by the clock "
                    "(default: can.sync_id of --config, if set)")
        ->check(CLI::Range(1, 0x7FF));
    cmd->add_option("--sync-timeout", o->sync_timeout, "with SYNC: seconds without one (after the first, which may take 30 s) that are an error")
        ->check(positive_number())
        ->capture_default_str();
    cmd->add_flag("--follow", o->follow,
                  "follow the controller's command frames (jacobid-fw playing a trajectory: each joint's newest commanded position and "
                  "velocity are the simulated robot's reference; it holds its start pose until the first) instead of random moves");
    cmd->add_flag("--quiet", o->quiet, "no start message");
    cmd->footer("Positions are quantized by the profile's own codes (MIT: 16 bit over the position range), not by an extra encoder model.");
}

}  // namespace jacobid::cli
