// SPDX-License-Identifier: MIT
#pragma once
// What trajectory playback plays and within which limits (fw.yaml `trajectory:`, docs/firmware.md,
// "Trajectory playback"): the table at the control rate and, per joint, the limits every cycle is
// checked against. Read once at start-up; TrajectoryPlayer only reads it.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "jacobid/fwconfig/capacity.hpp"
#include "jacobid/hal/joint_command.hpp"

namespace jacobid::firmware {

// One row per control cycle; joints beyond the robot's are unused.
struct TrajectoryRow {
    std::array<double, kMaxJoints> q{}, qd{}, tau{};  // rad, rad/s, N.m (feed-forward; 0 if not given)
    std::size_t line = 0;  // the row's line in the table file, for messages (0: not read from a file)
};

struct PlaybackConfig {
    std::string file;                 // the table's CSV (fw.yaml trajectory.file), for messages
    std::string log;                  // trajectory.log: commands beside measurements, CSV (empty: none)
    std::vector<TrajectoryRow> rows;  // at the control rate
    hal::CommandMode mode = hal::CommandMode::Position;
    double ramp_time = 3.0;  // s
    int repeat = 1;          // passes over the table
    std::array<double, kMaxJoints> position_min{}, position_max{}, velocity_limit{}, acceleration_limit{}, torque_limit{},
        following_error{};
    std::array<double, kMaxJoints> kp{}, kd{};  // MIT drives' own PD gains (device side), else ignored
    std::uint32_t max_stale_cycles = 0;
};

}  // namespace jacobid::firmware
