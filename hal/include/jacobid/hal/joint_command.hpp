// SPDX-License-Identifier: MIT
#pragma once
// One joint's command for trajectory playback, link side and profile-neutral: each profile's
// encode_command (hal/profiles/*.hpp) maps it to the device side with the joint's JointMapping and packs
// its own command frame (docs/profiles.md, "Command frames").
#include <cstdint>

namespace jacobid::hal {

enum class CommandMode : std::uint8_t {
    Position,  // position setpoint with velocity and torque feed-forward (MIT: + kp, kd)
    Torque,    // torque setpoint only
};

struct JointCommand {
    CommandMode mode = CommandMode::Position;
    double position = 0.0;  // rad, link side
    double velocity = 0.0;  // rad/s, link side (feed-forward)
    double torque = 0.0;    // N.m, link side (feed-forward, or the setpoint in Torque mode)
    // MIT mode only: the drive's own PD gains, device side (N.m/rad and N.m.s/rad at the actuator
    // output, the units of the drive's kp/kd ranges); the drive closes this loop, not the controller.
    double kp = 0.0;
    double kd = 0.0;
};

}  // namespace jacobid::hal
