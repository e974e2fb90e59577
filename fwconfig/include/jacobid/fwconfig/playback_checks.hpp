// SPDX-License-Identifier: MIT
#pragma once
#include <cstddef>
#include <string>

#include "jacobid/fwconfig/playback_config.hpp"

namespace jacobid::firmware {

// The start-up check of a playback: every row within the limits, and every step the player will command
// (along the table, from the ramp-in's end, at the wrap) within the velocity and acceleration limits at the
// control rate (trajectory_motion.hpp). "" or a one-line reason naming the table's file:line and joint.
// Shared by fw.yaml's parser (so jacobid-fw refuses before it opens anything) and configure() (the last
// gate before any command, whoever built the PlaybackConfig).
std::string check_playback(const PlaybackConfig& config, std::size_t joints, double sample_period);

}  // namespace jacobid::firmware
