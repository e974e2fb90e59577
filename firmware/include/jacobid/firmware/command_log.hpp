// SPDX-License-Identifier: MIT
#pragma once
// What trajectory playback commanded, beside what was measured in the same cycle (fw.yaml
// `trajectory.log`, docs/firmware.md "Trajectory playback"): one record per playback cycle, handed by the
// cycle to a CommandLog. The stream format v1 has no field for commands, so they go to their own file.
#include <array>
#include <cstddef>
#include <cstdint>

#include "jacobid/fwconfig/capacity.hpp"
#include "jacobid/firmware/trajectory_player.hpp"

namespace jacobid::firmware {

struct CommandRecord {
    std::int64_t time_ns = 0;  // the cycle's time
    PlaybackPhase phase = PlaybackPhase::Idle;
    StopReason reason = StopReason::None;
    std::size_t row = 0;  // table row (Playing)
    std::size_t joints = 0;
    std::array<double, kMaxJoints> measured{};  // q the cycle read, link side
    std::array<double, kMaxJoints> position{}, velocity{}, torque{};  // what was sent (the hold once stopped)
};

// Must not block or allocate (called from the cycle).
class CommandLog {
public:
    virtual ~CommandLog() = default;
    virtual void record(const CommandRecord& r) noexcept = 0;

protected:
    CommandLog() = default;
    CommandLog(const CommandLog&) = default;
    CommandLog& operator=(const CommandLog&) = default;
};

}  // namespace jacobid::firmware
