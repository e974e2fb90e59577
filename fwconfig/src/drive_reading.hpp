// SPDX-License-Identifier: MIT
#pragma once
// What a joint's drive reads from the command frames the firmware would send it, decided by the joint's
// profile itself (hal::encode_command, then the drive side's hal::decode_command), so that no profile's
// ranges, codes or modes are written in the firmware. Used when fw.yaml's `trajectory:` is read.
#include <cstddef>
#include <optional>
#include <string>

#include "jacobid/fwconfig/playback_config.hpp"
#include "jacobid/hal/joint_decoder_set.hpp"

namespace jacobid::firmware {

// Whether a position command with these gains reads as a position command (an MIT frame with kp = kd = 0
// is a torque command: the drive would hold no position).
bool reads_position_commands(const hal::ProfileConfig& joint, double kp, double kd);

// A trajectory limit the joint's command frames cannot carry: the encoder saturates before it, so a
// command at the limit would reach the drive as `carried` (e.g. an MIT position beyond its 16-bit range).
struct UncarriedLimit {
    const char* key;  // "position", "velocity", "torque", "kp", "kd"
    double asked;
    double carried;
};
// The first such limit of trajectory joint j, if any. A field the profile does not send at all (CiA 402
// has no velocity feed-forward) is not a saturation; neither is a wrapped position (a modulo counter).
std::optional<UncarriedLimit> uncarried_limit(const hal::ProfileConfig& joint, const PlaybackConfig& p, std::size_t j);

}  // namespace jacobid::firmware
