// SPDX-License-Identifier: MIT
#pragma once
// The motion a trajectory table commands, checked at start-up before anything moves (issue 36). The
// per-row checks (TrajectoryPlayer::configure) see each row alone; a 2 rad jump between two rows whose
// own values are within the limits passed them. Here every step between two consecutive *commanded*
// states is checked against the joint's limits at the control rate:
//   - along the table (row r -> r + 1),
//   - from the end of the ramp-in, which stands at rest on row 0, to row 1 (position mode),
//   - at the wrap from the last row to the next pass (repeat > 1), exactly as the player plays it.
// For each step: the position step over the row period against the velocity limit; the velocity
// column's change and the positions' second difference over the row period against the acceleration
// limit; and the velocity column against the position step (the drive gets both: a velocity column in
// other units, of another joint, or all zero would fight the position loop through the drive's kd).
//
// A wrap that is not smooth is refused, not ramped: a ramp would insert a motion that the table's designer
// (`jacobid excite`) did not optimise and whose duration and shape nobody chose, into data that is then
// identified as if it were the table; `jacobid excite` writes periodic tables (at rest at a pose at both
// ends), so a table that does not join its start is a mistake worth naming (docs/firmware.md).
#include <cstddef>
#include <string>

#include "jacobid/fwconfig/playback_config.hpp"

namespace jacobid::firmware {

// Relative tolerance on the velocity and acceleration limits: a sampled motion that respects a limit has
// steps within it exactly (mean value theorem); 1 % leaves room for a table whose limits were met at its
// samples only, and is far below any jump (a 2 rad step at 1 kHz is 2000 rad/s).
constexpr double kMotionLimitTolerance = 0.01;
// How exactly a table's positions are taken to be written (rad): 10 significant digits of a value near
// 1 rad. Its rounding enters each position step once and the second difference four times.
constexpr double kTablePositionResolution = 1e-9;

// The row each pass after the first starts at: 1 when the table ends where it starts (its last row is the
// first row's pose, which must not be commanded twice), else 0. The player and the check share it.
std::size_t next_pass_row(const PlaybackConfig& config, std::size_t joints) noexcept;

// "file:line: ..." of a table row (the row's number when it was not read from a file).
std::string table_location(const PlaybackConfig& config, std::size_t row);

// "" when every commanded step respects the limits, else one line naming the table file and line, the
// joint, the step and the limit (with the fw.yaml key), and what to change.
std::string check_trajectory_motion(const PlaybackConfig& config, std::size_t joints, double sample_period);

}  // namespace jacobid::firmware
