// SPDX-License-Identifier: MIT
// Firmware cycle cost (docs/performance.md, "Firmware cycle"): FirmwareCycle::step() for 6 MIT joints at
// 1 kHz, i.e. drain 6 frames from the virtual bus + decode + safety I/O (fake lines) + bank + datagram
// encode + publish. Variants split the cost: the simulator's sends alone, and a real UDP send over
// loopback (with the receiver's recv in the loop, so the socket buffer never fills).
#include <benchmark/benchmark.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cmath>
#include <memory>

#include "jacobid/fwconfig/firmware_config_yaml.hpp"
#include "jacobid/firmware/firmware_cycle.hpp"
#include "jacobid/firmware/runtime.hpp"
#include "jacobid/hal/virtual_can_bus.hpp"
#ifdef JACOBID_FW_MONITOR
#include <cstdio>

#include "monitor/firmware_monitor_model.hpp"
#endif

namespace {

using namespace jacobid;

struct NullPublisher final : firmware::Publisher {
    std::size_t bytes = 0;
    bool publish(Span<const std::uint8_t> d) noexcept override {
        bytes += d.size();
        return true;
    }
};
struct Line final : hal::InputLine, hal::OutputLine {
    hal::GpioStatus read(bool& level) noexcept override {
        level = true;
        return hal::GpioStatus::Ok;
    }
    hal::GpioStatus write(bool) noexcept override { return hal::GpioStatus::Ok; }
};

std::string six_joints() {
    std::string y = "can: {interface: virtual}\nrate: 1000\njoints:\n";
    for (int j = 1; j <= 6; ++j) y += "  - {profile: mit, motor_id: " + std::to_string(j) + "}\n";
    return y + "estimator: {position_window: 0.02, velocity_window: 0.05, acceleration_window: 0.1}\nstream: {host: 127.0.0.1, port: 9}\n";
}

struct Rig {
    hal::VirtualCanBus<2, 64> bus;
    hal::VirtualCanBus<2, 64>::Endpoint* fw = bus.attach();
    hal::VirtualCanBus<2, 64>::Endpoint* sim = bus.attach();
    Line line;
    hal::SafetyIo safety{line, line, line};
    firmware::FirmwareConfig config = firmware::parse_firmware_config(six_joints(), "bench.yaml");
    std::vector<std::array<hal::CanFrame, 6>> frames;  // 1000 cycles of a motion, pre-encoded
    std::unique_ptr<firmware::FirmwareCycle> cycle;
    std::int64_t now = 0;
    std::size_t k = 0;

    explicit Rig(firmware::Publisher& p, bool monitored = false) : cycle(std::make_unique<firmware::FirmwareCycle>(*fw, p, &safety)) {
        if (monitored) add_monitor();
        if (!cycle->configure(config).empty()) std::abort();
        cycle->reset_estop();
        frames.resize(1000);
        for (std::size_t i = 0; i < frames.size(); ++i) {
            for (std::size_t j = 0; j < 6; ++j) {
                const double t = static_cast<double>(i) * 1e-3;
                hal::mit::encode_reply(std::get<hal::mit::JointConfig>(config.joints[j].decoder), std::sin(6.0 * t + static_cast<double>(j)),
                                       6.0 * std::cos(6.0 * t), 10.0 * std::cos(3.0 * t), frames[i][j]);
            }
        }
    }
    // fw.yaml monitor: the UR5-like arm's description (6 joints, rotor inertias, smoothed Coulomb) and
    // thresholds no motion here reaches (action flag): the estimate, the detection and the stream fields run
    // every cycle, nothing stops.
    void add_monitor() {
#ifdef JACOBID_FW_MONITOR
        const std::string thresholds = "/tmp/jacobid-bench-monitor.yaml";
        std::string y = "estimator: {type: observer, gain: 100, velocity_window: 0.05}\njoints:\n";
        for (int j = 0; j < 6; ++j) y += "  - {moving: 1000, standing: 1000}\n";
        std::FILE* f = std::fopen(thresholds.c_str(), "w");
        if (f == nullptr) std::abort();
        std::fputs(y.c_str(), f);
        std::fclose(f);
        config.monitor.enabled = true;
        config.monitor.robot = std::string(JACOBID_EXAMPLES_DIR) + "/robots/ur5_like.yaml";
        config.monitor.thresholds = thresholds;
        config.monitor.action = firmware::MonitorAction::Flag;
        config.monitor.model = monitor::load_firmware_monitor(config).model;
#else
        std::abort();
#endif
    }
    void send() {
        for (const auto& f : frames[k % frames.size()]) sim->send(f);
        ++k;
    }
    void drain_only() {
        hal::CanFrame f;
        while (fw->receive(f) == hal::CanStatus::Ok) {
        }
    }
};

void BM_SimSend6Frames(benchmark::State& state) {
    NullPublisher p;
    Rig rig(p);
    for (auto _ : state) {
        rig.send();
        rig.drain_only();
    }
}
BENCHMARK(BM_SimSend6Frames);

// The cycle past its warm-up (full windows, datagrams every cycle), `monitored`: with the contact monitor.
void run_cycles(benchmark::State& state, bool monitored) {
    NullPublisher p;
    Rig rig(p, monitored);
    for (int i = 0; i < 200; ++i) {
        rig.send();
        rig.cycle->step(rig.now += 1'000'000);
    }
    for (auto _ : state) {
        rig.send();
        rig.cycle->step(rig.now += 1'000'000);
    }
    benchmark::DoNotOptimize(p.bytes);
    if (rig.cycle->counters().decode.decoded != 6 * rig.cycle->counters().cycles) state.SkipWithError("frames not decoded");
    const std::uint16_t version = monitored ? stream::kDatagramVersionMonitor : stream::kDatagramVersion;
    if (rig.cycle->last_datagram().version != version) state.SkipWithError("not the stream version asked for");
}

void BM_FirmwareCycle6Joints(benchmark::State& state) { run_cycles(state, false); }
BENCHMARK(BM_FirmwareCycle6Joints);

#ifdef JACOBID_FW_MONITOR
// The same with the contact monitor (fw.yaml monitor:): the momentum observer on the UR5-like arm's model
// (six Newton-Euler passes at the lib's 8-joint capacity), its detector and the version-2 datagram.
void BM_FirmwareCycle6JointsMonitor(benchmark::State& state) { run_cycles(state, true); }
BENCHMARK(BM_FirmwareCycle6JointsMonitor);
#endif

void BM_FirmwareCycle6JointsUdp(benchmark::State& state) {
    const int rx = ::socket(AF_INET, SOCK_DGRAM, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    socklen_t len = sizeof a;
    ::bind(rx, reinterpret_cast<sockaddr*>(&a), sizeof a);
    ::getsockname(rx, reinterpret_cast<sockaddr*>(&a), &len);
    firmware::UdpPublisher udp;
    if (!udp.open("127.0.0.1", ntohs(a.sin_port)).empty()) state.SkipWithError("udp");
    Rig rig(udp);
    std::array<std::uint8_t, 2048> buf{};
    for (auto _ : state) {
        rig.send();
        rig.cycle->step(rig.now += 1'000'000);
        while (::recv(rx, buf.data(), buf.size(), MSG_DONTWAIT) > 0) {
        }
    }
    ::close(rx);
    state.counters["publish_failures"] = static_cast<double>(rig.cycle->counters().publish_failures);
}
BENCHMARK(BM_FirmwareCycle6JointsUdp);

}  // namespace

BENCHMARK_MAIN();
