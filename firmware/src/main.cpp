// SPDX-License-Identifier: MIT
// jacobid-fw: the real-time firmware. Reads joint frames from a CAN interface at a fixed rate, runs the
// Jacobi streaming bank and publishes the aligned estimates as UDP datagrams (docs/firmware.md).
//
// Start-up (may allocate): config, CAN, GPIO, UDP, FirmwareCycle, real-time settings. Then the cycle loop,
// which allocates nothing: clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME) to the next period, step(),
// latency into a fixed histogram, overrun accounting. SIGINT/SIGTERM end the loop cleanly (drive enable
// dropped, log flushed, summary printed); SIGUSR1 asks for an e-stop reset.
#include <CLI/CLI.hpp>

#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <memory>
#include <optional>
#include <string>

#include "jacobid/fwconfig/firmware_config_yaml.hpp"
#include "jacobid/firmware/firmware_cycle.hpp"
#include "jacobid/firmware/jitter_stats.hpp"
#include "jacobid/firmware/runtime.hpp"
#include "jacobid/hal/gpiod_lines.hpp"
#include "jacobid/hal/socketcan_transport.hpp"
#include "jacobid/hal/virtual_can_bus.hpp"
#ifdef JACOBID_FW_MONITOR
#include "core/errors.hpp"
#include "monitor/firmware_monitor_model.hpp"
#endif

namespace {

using namespace jacobid;

volatile std::sig_atomic_t g_stop = 0;
volatile std::sig_atomic_t g_reset = 0;

extern "C" void on_stop(int sig) { g_stop = sig; }
extern "C" void on_reset(int) { g_reset = 1; }

constexpr int kExitConfig = 2;   // bad configuration (message names the key and line)
constexpr int kExitDevice = 1;   // CAN, GPIO or UDP could not be opened
constexpr int kExitPlaybackStopped = 4;  // trajectory playback stopped on a fault (the summary says which)

std::int64_t monotonic_ns() noexcept {
    timespec ts{};
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

timespec to_timespec(std::int64_t ns) noexcept {
    timespec ts{};
    ts.tv_sec = static_cast<time_t>(ns / 1'000'000'000);
    ts.tv_nsec = static_cast<long>(ns % 1'000'000'000);
    return ts;
}

// GPIO lines, opened from the config, or absent.
struct SafetyLines {
    hal::GpiodChip chip;
    hal::GpiodInputLine estop;
    hal::GpiodOutputLine enable, sync;
    std::optional<hal::SafetyIo> io;
};

// fw.yaml `monitor:`: the robot description and the monitor YAML, read by the host's readers (the code that
// wrote them); a build without the host tools has no reader and refuses the section.
bool load_monitor(firmware::FirmwareConfig& config) {
#ifdef JACOBID_FW_MONITOR
    try {
        monitor::FirmwareMonitorLoad load = monitor::load_firmware_monitor(config);
        config.monitor.model = std::move(load.model);
        for (const std::string& n : load.notes) std::fprintf(stderr, "jacobid-fw: warning: monitor: %s\n", n.c_str());
        return true;
    } catch (const InputError& e) {
        std::fprintf(stderr, "jacobid-fw: error: %s: monitor: %s\n", config.source.c_str(), e.what());
    } catch (const std::exception& e) {
        std::fprintf(stderr, "jacobid-fw: error: %s: monitor: %s\n", config.source.c_str(), e.what());
    }
    return false;
#else
    std::fprintf(stderr, "jacobid-fw: error: %s: monitor: this jacobid-fw was built without the host tools, which read the monitor's files\n",
                 config.source.c_str());
    return false;
#endif
}

int run(const std::string& config_path, double duration, bool no_realtime) {
    firmware::FirmwareConfig config;
    try {
        config = firmware::load_firmware_config(config_path);
    } catch (const firmware::ConfigError& e) {
        std::fprintf(stderr, "jacobid-fw: error: %s\n", e.what());
        return kExitConfig;
    }

    if (config.monitor.enabled && !load_monitor(config)) return kExitConfig;
    // Without a gpio: section the e-stop input and the drive enable do not exist: a playback on real drives
    // then stops only by its own checks and the hold command. Allowed (the drives may have their own safe
    // torque off), but said before anything moves.
    if (config.playback && !config.gpio.enabled && config.can_interface != "virtual") {
        std::fprintf(stderr, "jacobid-fw: warning: %s: trajectory playback without a gpio: section: no e-stop input and no drive enable; "
                             "a stop is only the hold command sent to the drives\n", config.source.c_str());
    }

    // CAN. "virtual" is a dry run on an in-process bus nobody else talks on: every joint stays stale, but
    // the loop, the stream and the statistics run as on the target.
    hal::VirtualCanBus<2, 256> virtual_bus;
    hal::SocketCanTransport socketcan;
    hal::CanTransport* can = nullptr;
    if (config.can_interface == "virtual") {
        can = virtual_bus.attach();
        std::fprintf(stderr, "jacobid-fw: warning: can.interface 'virtual': dry run, no device on the bus (every joint stale)\n");
    } else {
        hal::SocketCanConfig sc;
        sc.interface = config.can_interface.c_str();
        const hal::CanStatus s = socketcan.open(sc);
        if (s != hal::CanStatus::Ok) {
            std::fprintf(stderr, "jacobid-fw: error: %s: can.interface '%s': %s (errno %d)\n", config.source.c_str(),
                         config.can_interface.c_str(), hal::describe(s), socketcan.last_errno());
            return kExitDevice;
        }
        can = &socketcan;
    }

    SafetyLines lines;
    if (config.gpio.enabled) {
        const auto fail = [&](const char* what, hal::GpioStatus s) {
            std::fprintf(stderr, "jacobid-fw: error: %s: gpio %s on '%s': %s\n", config.source.c_str(), what, config.gpio.chip.c_str(),
                         hal::describe(s));
            return kExitDevice;
        };
        if (const auto s = lines.chip.open(config.gpio.chip.c_str()); s != hal::GpioStatus::Ok) return fail("chip", s);
        // Pull-down: a broken e-stop wire reads low = stop for the usual active-low chain.
        if (const auto s = lines.estop.open(lines.chip, config.gpio.estop_line, "jacobid-fw estop", hal::GpiodInputLine::Bias::PullDown);
            s != hal::GpioStatus::Ok)
            return fail("estop_line", s);
        if (const auto s = lines.enable.open(lines.chip, config.gpio.enable_line, "jacobid-fw enable", config.gpio.enable_active_low);
            s != hal::GpioStatus::Ok)
            return fail("enable_line", s);
        if (const auto s = lines.sync.open(lines.chip, config.gpio.sync_line, "jacobid-fw sync", false); s != hal::GpioStatus::Ok)
            return fail("sync_line", s);
        lines.io.emplace(lines.estop, lines.enable, lines.sync, hal::SafetyIoConfig{config.gpio.estop_active_low, config.gpio.enable_active_low});
    }

    firmware::UdpPublisher udp;
    if (const std::string e = udp.open(config.stream.host, config.stream.port); !e.empty()) {
        std::fprintf(stderr, "jacobid-fw: error: %s: %s\n", config.source.c_str(), e.c_str());
        return kExitDevice;
    }
    firmware::FilePublisher log;
    if (!config.stream.log.empty()) {
        if (const std::string e = log.open(config.stream.log); !e.empty()) {
            std::fprintf(stderr, "jacobid-fw: error: %s: %s\n", config.source.c_str(), e.c_str());
            return kExitDevice;
        }
    }
    firmware::TeePublisher publisher(udp, config.stream.log.empty() ? nullptr : &log);
    firmware::CsvCommandLog command_log;
    if (config.playback && !config.trajectory.log.empty()) {
        if (const std::string e = command_log.open(config.trajectory.log, config.joints.size()); !e.empty()) {
            std::fprintf(stderr, "jacobid-fw: error: %s: %s\n", config.source.c_str(), e.c_str());
            return kExitDevice;
        }
    }

    // ~0.3 MB of kernels and rings: on the heap, once.
    auto cycle = std::make_unique<firmware::FirmwareCycle>(*can, publisher, lines.io ? &*lines.io : nullptr);
    if (const std::string e = cycle->configure(config); !e.empty()) {
        std::fprintf(stderr, "jacobid-fw: error: %s: %s\n", config.source.c_str(), e.c_str());
        return kExitConfig;
    }
    if (config.playback && !config.trajectory.log.empty()) cycle->set_command_log(&command_log);
    // Starting the firmware is the operator's reset of the start-up latch; an e-stop pressed now stays.
    if (lines.io && !cycle->reset_estop()) {
        std::fprintf(stderr, "jacobid-fw: warning: e-stop active at start: drives stay disabled until it is released and reset (SIGUSR1)\n");
    }

    auto jitter = std::make_unique<firmware::JitterStats>();
    if (!no_realtime) {
        const firmware::RealtimeOutcome rt = firmware::apply_realtime(config.realtime);
        for (const std::string& w : rt.warnings) std::fprintf(stderr, "jacobid-fw: warning: %s\n", w.c_str());
        std::fprintf(stderr, "jacobid-fw: real-time: SCHED_FIFO %s, memory %s, CPU affinity %s\n", rt.fifo ? "on" : "off",
                     rt.locked ? "locked" : "not locked", rt.pinned ? "set" : "not set");
    }

    struct sigaction stop_action{};
    stop_action.sa_handler = on_stop;
    sigemptyset(&stop_action.sa_mask);
    sigaction(SIGINT, &stop_action, nullptr);
    sigaction(SIGTERM, &stop_action, nullptr);
    struct sigaction reset_action{};
    reset_action.sa_handler = on_reset;
    sigemptyset(&reset_action.sa_mask);
    sigaction(SIGUSR1, &reset_action, nullptr);

    std::fprintf(stderr, "jacobid-fw: %zu joint(s) on %s at %.0f Hz, estimates delayed %zu samples, streaming to %s:%u\n",
                 cycle->joint_count(), config.can_interface.c_str(), config.rate, cycle->delay_samples(), config.stream.host.c_str(),
                 static_cast<unsigned>(config.stream.port));

    // --- cycle loop: no allocation from here on ---
    const auto period = static_cast<std::int64_t>(1e9 / config.rate + 0.5);
    const auto report_every = static_cast<std::int64_t>(config.realtime.report_period * 1e9);
    const std::int64_t start = monotonic_ns();
    const std::int64_t end = duration > 0.0 ? start + static_cast<std::int64_t>(duration * 1e9) : 0;
    std::int64_t next = start + period;
    std::int64_t next_report = report_every > 0 ? start + report_every : 0;
    std::uint64_t overruns = 0;
    std::int64_t max_cost = 0;
    char line[1024];
    while (g_stop == 0) {
        const timespec wake = to_timespec(next);
        if (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &wake, nullptr) != 0) continue;  // EINTR: re-check g_stop
        const std::int64_t now = monotonic_ns();
        jitter->add(now - next);
        cycle->step(now);
        if (g_reset != 0) {
            g_reset = 0;
            std::fprintf(stderr, "jacobid-fw: e-stop reset %s\n", cycle->reset_estop() ? "done" : "refused (input still active)");
        }
        const std::int64_t done = monotonic_ns();
        if (done - now > max_cost) max_cost = done - now;
        next += period;
        // Overrun: the cycle finished after the next deadline. Skip the missed periods (they are lost
        // samples, visible as missing sample indices in the stream) rather than running them back to back.
        while (next <= done) {
            next += period;
            ++overruns;
            cycle->note_missed_deadline();
        }
        if (next_report != 0 && now >= next_report) {
            next_report += report_every;
            std::fprintf(stderr, "jacobid-fw: %s, max cycle cost %.1f us\n", firmware::format_jitter(*jitter, overruns, line, sizeof line),
                         static_cast<double>(max_cost) / 1e3);
        }
        if (end != 0 && now >= end) break;
    }
    // --- shutdown ---
    cycle->stop();
    if (!config.stream.log.empty()) log.flush();
    if (config.playback && !config.trajectory.log.empty()) {
        if (!command_log.flush() || command_log.failures() != 0) {
            std::fprintf(stderr, "jacobid-fw: warning: trajectory.log %s: %llu rows not written\n", config.trajectory.log.c_str(),
                         static_cast<unsigned long long>(command_log.failures()));
        }
    }
    std::fprintf(stderr, "jacobid-fw: stopped (%s)\n", g_stop == SIGINT ? "SIGINT" : g_stop == SIGTERM ? "SIGTERM" : "--duration");
    std::fprintf(stderr, "jacobid-fw: %s, max cycle cost %.1f us\n", firmware::format_jitter(*jitter, overruns, line, sizeof line),
                 static_cast<double>(max_cost) / 1e3);
    std::fprintf(stderr, "jacobid-fw: %s\n", firmware::format_counters(cycle->counters(), cycle->joint_count(), line, sizeof line));
    if (cycle->playback()) std::fprintf(stderr, "jacobid-fw: %s\n", firmware::format_playback(cycle->player(), cycle->counters(), line, sizeof line));
    if (cycle->monitor().enabled()) std::fprintf(stderr, "jacobid-fw: %s\n", firmware::format_monitor(*cycle, line, sizeof line));
    return cycle->playback() && cycle->player().phase() == firmware::PlaybackPhase::Stopped ? kExitPlaybackStopped : 0;
}

// --duration: seconds >= 0 (0: until a signal), at most 1e9 s (31 years) so that the deadline in nanoseconds
// stays far inside an int64; a negative or non-finite value would otherwise mean "run forever".
constexpr double kMaxDurationSeconds = 1e9;

std::string check_duration(const std::string& text) {
    char* end = nullptr;
    const double value = std::strtod(text.c_str(), &end);
    if (text.empty() || *end != '\0' || !std::isfinite(value) || value < 0.0 || value > kMaxDurationSeconds) {
        return "expected a number of seconds in [0, 1e9] (0: run until SIGINT/SIGTERM), got '" + text + "'";
    }
    return {};
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"jacobid-fw: real-time joint-state firmware: CAN -> Jacobi streaming bank -> UDP estimate datagrams"};
    std::string config;
    double duration = 0.0;
    bool no_realtime = false;
    app.add_option("--config,-c", config, "firmware configuration (YAML, see docs/firmware.md)")->required();
    app.add_option("--duration", duration, "stop after this many seconds (0: run until SIGINT/SIGTERM)")
        ->check(CLI::Validator(check_duration, "SECONDS"))
        ->capture_default_str();
    app.add_flag("--no-realtime", no_realtime, "do not ask for SCHED_FIFO, mlockall or CPU affinity");
    app.footer("Signals: SIGINT/SIGTERM stop cleanly (drive enable dropped, summary printed); SIGUSR1 resets a released e-stop.\n"
               "Exit codes: 0 ok, 1 device (CAN, GPIO, UDP) could not be opened, 2 configuration error, 4 trajectory playback stopped on "
               "a fault (e-stop, contact, missed deadline, drive fault, stale joint, following error, limit).");
    try {
        app.parse(argc, argv);
    } catch (const CLI::Success& e) {
        return app.exit(e);  // --help: printed, exit 0
    } catch (const CLI::ParseError& e) {
        // An unknown option, a missing or refused value: a configuration error, on one line.
        std::fprintf(stderr, "jacobid-fw: error: %s\n", e.what());
        return kExitConfig;
    }
    return run(config, duration, no_realtime);
}
