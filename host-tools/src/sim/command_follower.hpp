// SPDX-License-Identifier: MIT
#pragma once
// The simulated drives following a controller's commands (`jacobid sim-can --follow`, issue 17): at each
// control instant of the closed loop, the command frames that arrived on the bus are decoded with each
// joint's profile (hal::decode_command, the drive side of hal/profiles/*.hpp) and the newest position and
// velocity of each joint become the simulator's reference; until a joint's first command, the robot holds
// its start pose. So jacobid-fw playing a trajectory -> CAN -> the simulated robot -> CAN -> jacobid-fw is
// a loop closed by the robot's dynamics.
#include <cstdint>
#include <vector>

#include "jacobid/hal/can_transport.hpp"
#include "jacobid/hal/profile_registry.hpp"
#include "sim/quintic_trajectory.hpp"

namespace jacobid::sim {

struct CommandFollowerCounters {
    std::uint64_t frames = 0;          // frames read from the bus
    std::uint64_t commands = 0;        // frames decoded as a joint's command
    std::uint64_t rejected = 0;        // frames a joint's decoder claimed but could not decode
    std::vector<std::uint64_t> joint_commands;  // per joint
};

class CommandFollower {
public:
    // One profile config per joint (the firmware's), `start` the pose held before the first command (rad).
    CommandFollower(hal::CanTransport& can, std::vector<hal::ProfileConfig> joints, std::vector<double> start);

    // The simulator's reference at a control instant: reads every pending frame first.
    void reference(double t, ReferenceSample& out);
    // One frame read elsewhere (e.g. while waiting for a SYNC on the same socket).
    void take(const hal::CanFrame& frame);

    const CommandFollowerCounters& counters() const { return counters_; }

private:
    hal::CanTransport& can_;
    std::vector<hal::ProfileConfig> joints_;
    std::vector<double> q_, qd_;
    CommandFollowerCounters counters_;
};

}  // namespace jacobid::sim
