// SPDX-License-Identifier: MIT
#include "sim/command_follower.hpp"

#include <utility>

namespace jacobid::sim {

CommandFollower::CommandFollower(hal::CanTransport& can, std::vector<hal::ProfileConfig> joints, std::vector<double> start)
    : can_(can), joints_(std::move(joints)), q_(std::move(start)), qd_(q_.size(), 0.0) {
    counters_.joint_commands.assign(joints_.size(), 0);
}

void CommandFollower::take(const hal::CanFrame& f) {
    ++counters_.frames;
    for (std::size_t j = 0; j < joints_.size(); ++j) {
        hal::JointCommand c;
        const hal::DecodeStatus s = hal::decode_command(joints_[j], hal::CommandMode::Position, f, c);
        if (s == hal::DecodeStatus::NotMine) continue;
        if (s != hal::DecodeStatus::Ok) {
            ++counters_.rejected;
            return;
        }
        // A position command steers the reference; a torque-only one (torque mode) holds the pose.
        if (c.mode == hal::CommandMode::Position) {
            q_[j] = c.position;
            qd_[j] = c.velocity;
        }
        ++counters_.commands;
        ++counters_.joint_commands[j];
        return;
    }
}

void CommandFollower::reference(double, ReferenceSample& out) {
    hal::CanFrame f;
    while (can_.receive(f) == hal::CanStatus::Ok) take(f);
    out.q = q_;
    out.qd = qd_;
    out.qdd.assign(q_.size(), 0.0);
}

}  // namespace jacobid::sim
