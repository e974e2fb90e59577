// SPDX-License-Identifier: MIT
#pragma once
// Trajectory playback on the controller (issue 17): each cycle, the link-side command of every joint from
// a table at the control rate (`jacobid excite`'s CSV: t, q, qd, qdd per joint), after a ramp from the pose
// the robot stands at, with the safety checks a real drive needs. The player decides; the firmware cycle
// encodes its commands with each joint's profile (hal/profiles/*.hpp encode_command) and sends them.
//
// Phases: Idle -> (start) -> RampIn -> Playing -> Finished, or Stopped from any active phase. RampIn goes
// from the measured pose of its first cycle to the table's first row along a quintic (at rest at both
// ends) in `ramp_time`; Playing steps one table row per cycle, `repeat` times. Every active cycle checks,
// in this order, and stops in that same cycle on the first failure (the command becomes "stop", latched
// until configure/start):
//   e-stop input, a contact (the monitor's), a missed cycle deadline, a drive fault, a joint not fresh for more than
//   `max_stale_cycles`, the following error |measured - previous command| above `following_error`, the
//   command's position outside [position_min, position_max], |velocity| above `velocity_limit`,
//   |feed-forward torque| above `torque_limit`. The ramp's first cycle also checks the quintic's peak
//   velocity and acceleration against the limits; every step of the table itself was checked at configure.
// Model/Data split: configure() copies the table (start-up, may allocate); step() allocates nothing and
// never throws.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>

#include "jacobid/fwconfig/capacity.hpp"
#include "jacobid/fwconfig/playback_checks.hpp"
#include "jacobid/fwconfig/playback_config.hpp"
#include "jacobid/hal/joint_command.hpp"

namespace jacobid::firmware {

enum class PlaybackPhase : std::uint8_t { Idle, RampIn, Playing, Finished, Stopped };
enum class StopReason : std::uint8_t {
    None,
    EStop,
    MissedDeadline,
    DriveFault,
    StaleJoint,
    FollowingError,
    PositionLimit,
    VelocityLimit,
    AccelerationLimit,  // the ramp-in from where the robot stands (checked in its first cycle)
    TorqueLimit,
    Contact,  // the contact monitor (fw.yaml `monitor:`) confirmed a contact in this cycle
};
const char* to_string(PlaybackPhase phase) noexcept;
const char* to_string(StopReason reason) noexcept;

struct PlayerInput {
    std::array<double, kMaxJoints> q{};     // measured, link side
    std::array<bool, kMaxJoints> fresh{};   // a new measurement this cycle
    std::array<bool, kMaxJoints> fault{};   // the drive reports a fault
    bool estop = false;
    bool deadline_missed = false;
    int contact_joint = -1;  // 0-based joint the contact monitor found in contact this cycle; -1: none
};

class TrajectoryPlayer {
public:
    // check_playback(), then copies the table. Returns "" or its one-line reason (and plays nothing).
    std::string configure(const PlaybackConfig& config, std::size_t joints, double sample_period);
    // Arms the player: the next step() starts the ramp from the measured pose.
    void start() noexcept;
    // One cycle: the commands to send (meaningful while active()), or a stop.
    void step(const PlayerInput& in) noexcept;

    bool active() const noexcept { return phase_ == PlaybackPhase::RampIn || phase_ == PlaybackPhase::Playing; }
    // True once stopped (latched): the firmware sends each drive's stop instead of a command.
    bool stop_drives() const noexcept { return phase_ == PlaybackPhase::Stopped; }
    PlaybackPhase phase() const noexcept { return phase_; }
    StopReason stop_reason() const noexcept { return reason_; }
    int stop_joint() const noexcept { return stop_joint_; }  // 0-based; -1: not a joint's
    const std::array<hal::JointCommand, kMaxJoints>& commands() const noexcept { return commands_; }
    std::uint64_t cycles() const noexcept { return cycles_; }
    std::size_t row() const noexcept { return row_; }  // table row of the last Playing cycle
    const PlaybackConfig& config() const noexcept { return config_; }

private:
    void stop(StopReason reason, int joint) noexcept;
    bool check_input(const PlayerInput& in) noexcept;
    bool check_command() noexcept;

    PlaybackConfig config_;
    std::size_t joints_ = 0;
    double sample_period_ = 0.0;
    PlaybackPhase phase_ = PlaybackPhase::Idle;
    StopReason reason_ = StopReason::None;
    int stop_joint_ = -1;
    std::array<hal::JointCommand, kMaxJoints> commands_{};
    std::array<double, kMaxJoints> ramp_start_{};
    std::array<std::uint32_t, kMaxJoints> stale_{};
    std::uint64_t cycles_ = 0;      // active cycles since start
    std::uint64_t ramp_cycles_ = 0;
    std::size_t row_ = 0;
    std::size_t next_pass_row_ = 0;  // where each pass after the first starts (next_pass_row)
    int pass_ = 0;
    bool has_command_ = false;  // a previous command exists (for the following error)
};

}  // namespace jacobid::firmware
