// SPDX-License-Identifier: MIT
#include "jacobid/fwconfig/playback_checks.hpp"

#include <fmt/core.h>

#include <cmath>

#include "jacobid/fwconfig/capacity.hpp"
#include "jacobid/fwconfig/trajectory_motion.hpp"

namespace jacobid::firmware {

std::string check_playback(const PlaybackConfig& config, std::size_t joints, double sample_period) {
    if (joints == 0 || joints > kMaxJoints) return "trajectory: " + std::to_string(joints) + " joints (1.." + std::to_string(kMaxJoints) + ")";
    if (!(sample_period > 0.0)) return "trajectory: the sample period must be > 0";
    if (config.rows.size() < 2) return "trajectory: the table needs at least two rows";
    if (config.repeat < 1) return "trajectory: repeat " + std::to_string(config.repeat) + ", expected >= 1";
    if (config.mode == hal::CommandMode::Position && !(config.ramp_time > 0.0 && std::isfinite(config.ramp_time))) {
        return "trajectory: ramp_time must be a finite time > 0 s";
    }
    for (std::size_t j = 0; j < joints; ++j) {
        const std::string joint = "trajectory: joint " + std::to_string(j + 1) + ": ";
        if (!(config.position_min[j] < config.position_max[j])) return joint + "position limits [min, max] with min < max are required";
        if (!(config.velocity_limit[j] > 0.0)) return joint + "velocity_limit > 0 is required";
        if (!(config.acceleration_limit[j] > 0.0)) return joint + "acceleration_limit > 0 is required";
        if (!(config.torque_limit[j] > 0.0)) return joint + "torque_limit > 0 is required";
        if (!(config.following_error[j] > 0.0)) return joint + "following_error > 0 is required";
        for (std::size_t r = 0; r < config.rows.size(); ++r) {
            const TrajectoryRow& row = config.rows[r];
            const std::string where = table_location(config, r) + ": joint " + std::to_string(j + 1) + ": ";
            if (!std::isfinite(row.q[j]) || !std::isfinite(row.qd[j]) || !std::isfinite(row.tau[j])) return where + "not a finite number";
            if (row.q[j] < config.position_min[j] || row.q[j] > config.position_max[j]) {
                return where + fmt::format("position {:.6g} rad outside the limits [{:.6g}, {:.6g}] rad (trajectory.joints[{}].position)", row.q[j],
                                           config.position_min[j], config.position_max[j], j);
            }
            if (std::abs(row.qd[j]) > config.velocity_limit[j]) {
                return where + fmt::format("velocity {:.6g} rad/s beyond the limit {:.6g} rad/s (trajectory.joints[{}].velocity)", row.qd[j], config.velocity_limit[j], j);
            }
            if (std::abs(row.tau[j]) > config.torque_limit[j]) {
                return where + fmt::format("torque {:.6g} N.m beyond the limit {:.6g} N.m (trajectory.joints[{}].torque)", row.tau[j], config.torque_limit[j], j);
            }
        }
    }
    // Each row is within the limits; now every step between the rows the player will command.
    return check_trajectory_motion(config, joints, sample_period);
}

}  // namespace jacobid::firmware
