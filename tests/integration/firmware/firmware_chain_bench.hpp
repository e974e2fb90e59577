// SPDX-License-Identifier: MIT
#pragma once
// The firmware chain on the virtual bus, shared by the chain and the monitor tests: the closed-loop 2R
// simulator (the paper's Table II robot) -> MIT telemetry frames (CanPlayer, the core of `jacobid sim-can`)
// -> FirmwareCycle, one cycle per simulated sample at 1 kHz simulated time.
#include <gtest/gtest.h>

#include <chrono>
#include <functional>
#include <memory>
#include <thread>

#include "firmware_test_support.hpp"
#include "robot/planar2r_model.hpp"
#include "robot/robot_description.hpp"
#include "sim/can_player.hpp"
#include "sim/simulator.hpp"

namespace jacobid::test {

inline Eigen::VectorXd table2(const robot::RobotModel& model) {
    const auto* planar = dynamic_cast<const robot::Planar2RModel*>(&model);
    const auto t = robot::paper_table2_parameters(*planar);
    return Eigen::Map<const Eigen::VectorXd>(t.data(), static_cast<Eigen::Index>(t.size()));
}

// The chain's pieces on the virtual bus: the MIT 2R firmware (`config`, e.g. with a trajectory:), its GPIO
// released, and the simulated drives' telemetry (CanPlayer, the core of `jacobid sim-can`) on the other end.
struct ChainBench : BenchWiring {
    std::unique_ptr<firmware::FirmwareCycle> cycle;
    sim::CanPlayer player;
    const robot::RobotDescription robot = robot::default_planar2r_description();
    const std::unique_ptr<robot::RobotModel> model = robot::make_robot_model(robot);
    std::uint64_t samples = 0;
    std::uint64_t noise_seed = 8;  // the measurement noise's
    // Called after each cycle with the sample the drives sent before it (its truth) and the cycle's time.
    std::function<void(const sim::SimulatedSample&, std::int64_t now_ns)> after_step;

    ChainBench(firmware::Publisher& publisher, const firmware::FirmwareConfig& config)
        : cycle(std::make_unique<firmware::FirmwareCycle>(*fw_end, publisher, &safety)), player(*sim_end, profiles_of(config)) {
        EXPECT_EQ(cycle->configure(config), "");
        EXPECT_TRUE(cycle->reset_estop());
    }

    // The Table II robot simulated with `settings` (torque noise 0.05 / 0.01 N.m; the MIT position code is the
    // encoder), each sample sent as telemetry and followed by one firmware cycle at 1 kHz simulated time;
    // `pace_hz` > 0 sleeps so that the datagrams leave at that rate in wall time.
    void simulate(const sim::SimulationSettings& settings, double pace_hz = 0.0) {
        sim::MeasurementSettings ms;
        ms.encoder_counts_per_rev = 0.0;
        ms.torque_noise = {0.05, 0.01};
        ms.seed = noise_seed;
        sim::MeasurementModel measurement(ms);
        const auto start = std::chrono::steady_clock::now();
        sim::simulate(*model, table2(*model), robot.joints, settings, measurement, [&](const sim::SimulatedSample& s) {
            const auto now = static_cast<std::int64_t>(samples) * 1'000'000;
            bus.set_time_ns(now);
            player.send(s.q.data(), s.qd.data(), s.tau_measured.data());
            cycle->step(now);
            if (after_step) after_step(s, now);
            ++samples;
            if (pace_hz > 0.0) std::this_thread::sleep_until(start + std::chrono::duration<double>(static_cast<double>(samples) / pace_hz));
        });
    }
};

}  // namespace jacobid::test
