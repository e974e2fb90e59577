// SPDX-License-Identifier: MIT
#pragma once
// Shared pieces of the firmware tests: fake GPIO lines, an in-memory publisher that decodes what the cycle
// sends, a transport decorator that injects faults, and the test firmware configuration.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "jacobid/fwconfig/firmware_config_yaml.hpp"
#include "jacobid/firmware/firmware_cycle.hpp"
#include "jacobid/hal/gpio.hpp"
#include "jacobid/hal/virtual_can_bus.hpp"
#include "jacobid/stream/estimate_datagram.hpp"

namespace jacobid::test {

struct FakeInput final : hal::InputLine {
    bool level = true;  // released for the active-low e-stop
    hal::GpioStatus status = hal::GpioStatus::Ok;
    hal::GpioStatus read(bool& out) noexcept override {
        out = level;
        return status;
    }
};

struct FakeOutput final : hal::OutputLine {
    bool level = false;
    std::uint64_t writes = 0;
    hal::GpioStatus write(bool l) noexcept override {
        level = l;
        ++writes;
        return hal::GpioStatus::Ok;
    }
};

// Keeps the last datagram (decoded) and counts; optionally forwards the bytes. publish() allocates
// nothing when no callback is set (the zero-allocation test uses it that way).
class MemoryPublisher final : public firmware::Publisher {
public:
    std::function<void(Span<const std::uint8_t>)> on_datagram;
    stream::EstimateDatagram<firmware::kMaxJoints> last{};
    stream::DatagramStatus last_status = stream::DatagramStatus::Ok;
    std::uint64_t count = 0;
    bool refuse = false;

    bool publish(Span<const std::uint8_t> d) noexcept override {
        if (refuse) return false;
        ++count;
        last_status = stream::decode(d, last);
        if (on_datagram) on_datagram(d);
        return true;
    }
};

using TestBus = hal::VirtualCanBus<4, 64>;

// Sits between the simulator's endpoint and the bus and breaks the traffic on purpose.
class FaultyTransport final : public hal::CanTransport {
public:
    explicit FaultyTransport(hal::CanTransport& inner) : inner_(inner) {}
    // Decides per frame: return false to drop it; may modify it (garbage) or ask for a duplicate.
    std::function<bool(hal::CanFrame&, bool& duplicate)> rule;

    hal::CanStatus send(const hal::CanFrame& frame) noexcept override {
        hal::CanFrame f = frame;
        bool duplicate = false;
        if (rule && !rule(f, duplicate)) return hal::CanStatus::Ok;  // lost on the wire: the sender cannot tell
        const hal::CanStatus s = inner_.send(f);
        if (duplicate) inner_.send(f);
        return s;
    }
    hal::CanStatus receive(hal::CanFrame& frame) noexcept override { return inner_.receive(frame); }
    const hal::CanCounters& counters() const noexcept override { return inner_.counters(); }
    bool is_open() const noexcept override { return inner_.is_open(); }

private:
    hal::CanTransport& inner_;
};

// The firmware's surroundings in a test: a virtual bus with the firmware's end and the drives' end, and the
// safety I/O on fake lines (e-stop released).
struct BenchWiring {
    TestBus bus;
    TestBus::Endpoint* fw_end = bus.attach();
    TestBus::Endpoint* sim_end = bus.attach();
    FakeInput estop;
    FakeOutput enable, sync;
    hal::SafetyIo safety{estop, enable, sync};
};

// The chain's firmware configuration: MIT actuators behind a 4:1 reducer; joint 1 a big actuator
// (+-30 N.m motor side = +-120 N.m on the link, the 2R robot needs up to ~113), joint 2 a small one
// (+-2 N.m = +-8 N.m link, it needs ~5.5). One position code = 25 / 65535 / 4 = 9.5e-5 rad on the link,
// the resolution of a 2^16 counts/rev encoder (9.6e-5 rad).
inline std::string chain_config_yaml(const std::string& extra = "") {
    return "can: {interface: virtual}\n"
           "rate: 1000\n"
           "joints:\n"
           "  - {name: shoulder, profile: mit, motor_id: 1, gear_ratio: 4, velocity_range: [-65, 65], effort_range: [-30, 30]}\n"
           "  - {name: elbow, profile: mit, motor_id: 2, gear_ratio: 4, velocity_range: [-65, 65], effort_range: [-2, 2]}\n"
           "estimator: {position_window: 0.02, velocity_window: 0.05, acceleration_window: 0.1}\n"
           "stream: {host: 127.0.0.1, port: 5005}\n" +
           extra;
}

inline firmware::FirmwareConfig chain_config(const std::string& extra = "") {
    return firmware::parse_firmware_config(chain_config_yaml(extra), "fw.yaml");
}

inline std::vector<hal::ProfileConfig> profiles_of(const firmware::FirmwareConfig& c) {
    std::vector<hal::ProfileConfig> p;
    for (const auto& j : c.joints) p.push_back(j.decoder);
    return p;
}

}  // namespace jacobid::test
