// SPDX-License-Identifier: MIT
#include "jacobid/firmware/trajectory_player.hpp"

#include "jacobid/fwconfig/trajectory_motion.hpp"

#include <fmt/core.h>

#include <cmath>
#include <string>

namespace jacobid::firmware {
namespace {

// Quintic blend at rest at both ends: s(0) = 0, s(1) = 1, s' and s'' zero at both ends.
double blend(double u) noexcept { return u * u * u * (10.0 + u * (-15.0 + 6.0 * u)); }
double blend_rate(double u) noexcept { return 30.0 * u * u * (1.0 - u) * (1.0 - u); }

// The quintic's peaks over [0, 1]: s' at u = 1/2, s'' at u = 1/2 - sqrt(3)/6.
constexpr double kBlendPeakRate = 1.875;
constexpr double kBlendPeakAcceleration = 5.773502691896258;  // 10 / sqrt(3)

}  // namespace

const char* to_string(PlaybackPhase phase) noexcept {
    switch (phase) {
        case PlaybackPhase::Idle: return "idle";
        case PlaybackPhase::RampIn: return "ramp-in";
        case PlaybackPhase::Playing: return "playing";
        case PlaybackPhase::Finished: return "finished";
        case PlaybackPhase::Stopped: return "stopped";
    }
    return "?";
}

const char* to_string(StopReason reason) noexcept {
    switch (reason) {
        case StopReason::None: return "none";
        case StopReason::EStop: return "e-stop";
        case StopReason::MissedDeadline: return "missed cycle deadline";
        case StopReason::DriveFault: return "drive fault";
        case StopReason::StaleJoint: return "stale joint";
        case StopReason::FollowingError: return "following error";
        case StopReason::PositionLimit: return "position limit";
        case StopReason::VelocityLimit: return "velocity limit";
        case StopReason::AccelerationLimit: return "acceleration limit";
        case StopReason::TorqueLimit: return "torque limit";
        case StopReason::Contact: return "contact";
    }
    return "?";
}

std::string TrajectoryPlayer::configure(const PlaybackConfig& config, std::size_t joints, double sample_period) {
    phase_ = PlaybackPhase::Idle;
    reason_ = StopReason::None;
    stop_joint_ = -1;
    joints_ = 0;  // until accepted: start() does nothing
    if (std::string why = check_playback(config, joints, sample_period); !why.empty()) return why;
    config_ = config;
    joints_ = joints;
    sample_period_ = sample_period;
    next_pass_row_ = next_pass_row(config, joints);
    return "";
}

void TrajectoryPlayer::start() noexcept {
    if (joints_ == 0) return;
    phase_ = config_.mode == hal::CommandMode::Position ? PlaybackPhase::RampIn : PlaybackPhase::Playing;
    reason_ = StopReason::None;
    stop_joint_ = -1;
    stale_ = {};
    cycles_ = 0;
    ramp_cycles_ = static_cast<std::uint64_t>(std::ceil(config_.ramp_time / sample_period_));
    row_ = 0;
    pass_ = 0;
    has_command_ = false;
}

void TrajectoryPlayer::stop(StopReason reason, int joint) noexcept {
    phase_ = PlaybackPhase::Stopped;
    reason_ = reason;
    stop_joint_ = joint;
}

bool TrajectoryPlayer::check_input(const PlayerInput& in) noexcept {
    // A contact first: its action also trips the e-stop line in the same cycle, and the stop's reason is the contact.
    if (in.contact_joint >= 0) return stop(StopReason::Contact, in.contact_joint), false;
    if (in.estop) return stop(StopReason::EStop, -1), false;
    if (in.deadline_missed) return stop(StopReason::MissedDeadline, -1), false;
    for (std::size_t j = 0; j < joints_; ++j) {
        if (in.fault[j]) return stop(StopReason::DriveFault, static_cast<int>(j)), false;
    }
    for (std::size_t j = 0; j < joints_; ++j) {
        stale_[j] = in.fresh[j] ? 0 : stale_[j] + 1;
        if (stale_[j] > config_.max_stale_cycles) return stop(StopReason::StaleJoint, static_cast<int>(j)), false;
    }
    // The measured position answers the commands sent before it: compared with the previous command.
    for (std::size_t j = 0; j < joints_ && has_command_; ++j) {
        if (!(std::abs(in.q[j] - commands_[j].position) <= config_.following_error[j])) return stop(StopReason::FollowingError, static_cast<int>(j)), false;
    }
    return true;
}

bool TrajectoryPlayer::check_command() noexcept {
    for (std::size_t j = 0; j < joints_; ++j) {
        const hal::JointCommand& c = commands_[j];
        const int joint = static_cast<int>(j);
        if (!(c.position >= config_.position_min[j] && c.position <= config_.position_max[j])) return stop(StopReason::PositionLimit, joint), false;
        if (!(std::abs(c.velocity) <= config_.velocity_limit[j])) return stop(StopReason::VelocityLimit, joint), false;
        if (!(std::abs(c.torque) <= config_.torque_limit[j])) return stop(StopReason::TorqueLimit, joint), false;
    }
    return true;
}

void TrajectoryPlayer::step(const PlayerInput& in) noexcept {
    if (!active()) return;
    if (!check_input(in)) return;
    ++cycles_;
    const std::size_t n = config_.rows.size();
    if (phase_ == PlaybackPhase::RampIn) {
        if (cycles_ == 1) {
            // The quintic's peak velocity, 15/8 distance / ramp_time, and peak acceleration, 10/sqrt(3)
            // distance / ramp_time^2: refused before the first move. (Its end, at rest on row 0, and the step
            // on to row 1 are checked at configure: check_trajectory_motion.)
            for (std::size_t j = 0; j < joints_; ++j) {
                ramp_start_[j] = in.q[j];
                const double distance = std::abs(config_.rows.front().q[j] - in.q[j]);
                if (kBlendPeakRate * distance / config_.ramp_time > config_.velocity_limit[j]) return stop(StopReason::VelocityLimit, static_cast<int>(j));
                if (kBlendPeakAcceleration * distance / (config_.ramp_time * config_.ramp_time) > config_.acceleration_limit[j]) {
                    return stop(StopReason::AccelerationLimit, static_cast<int>(j));
                }
            }
        }
        const double u = static_cast<double>(cycles_) / static_cast<double>(ramp_cycles_);
        const TrajectoryRow& first = config_.rows.front();
        for (std::size_t j = 0; j < joints_; ++j) {
            hal::JointCommand& c = commands_[j];
            const double distance = first.q[j] - ramp_start_[j];
            c = hal::JointCommand{hal::CommandMode::Position, ramp_start_[j] + distance * blend(u), distance * blend_rate(u) / config_.ramp_time, 0.0,
                                  config_.kp[j], config_.kd[j]};
        }
        if (cycles_ >= ramp_cycles_) phase_ = PlaybackPhase::Playing;  // this cycle commanded row 0 exactly
    } else {
        // The row after the last commanded one; a table that ends where it starts repeats without its first row.
        const bool first_command = !has_command_;
        if (first_command && config_.mode == hal::CommandMode::Torque) {
            row_ = 0;
        } else if (row_ + 1 < n) {
            ++row_;
        } else if (pass_ + 1 < config_.repeat) {
            ++pass_;
            row_ = next_pass_row_;
        } else {
            phase_ = PlaybackPhase::Finished;
            return;
        }
        const TrajectoryRow& r = config_.rows[row_];
        for (std::size_t j = 0; j < joints_; ++j) {
            commands_[j] = hal::JointCommand{config_.mode, r.q[j], r.qd[j], r.tau[j], config_.kp[j], config_.kd[j]};
        }
    }
    has_command_ = true;
    check_command();
}

}  // namespace jacobid::firmware
