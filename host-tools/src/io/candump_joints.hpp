// SPDX-License-Identifier: MIT
#pragma once
// Joint positions and torques from a candump capture: the frames are decoded by the same HAL device
// profiles as the firmware's, and grouped into samples (one per controller cycle), so a capture taken on
// a robot can be identified off-line with `jacobid identify --can-config fw.yaml --in capture.log`.
//
// A sample is complete when every joint has delivered its position and its torque (one MIT/CiA 402 frame,
// or ODrive's encoder-estimate + Iq pair); its time is that of the cycle's first frame. A joint that
// delivers twice before the others complete the cycle means a frame was lost: an InputError names the
// line. Frames on identifiers no joint uses (other devices on the bus) and error frames are skipped and
// counted; any frame a joint's decoder rejects (short, out of range) is an InputError naming the line.
#include <cstdint>
#include <string>
#include <vector>

#include "io/candump_log.hpp"
#include "io/csv_table.hpp"
#include "jacobid/hal/joint_decoder_set.hpp"

namespace jacobid::io {

struct CandumpJointCounts {
    std::size_t samples = 0;
    std::size_t frames_decoded = 0;
    std::size_t frames_other_ids = 0;  // identifiers no joint listens to
    std::size_t error_frames = 0;
    // The samples' times: a capture's stamps are the host's receive times, which jitter around the
    // controller's cycle. Stamps within kCycleJitterTolerance cycles of a uniform grid are replaced by
    // that grid (the nominal cycle), and the largest deviation is reported here.
    double cycle = 0.0;       // s, the fitted cycle
    double max_jitter = 0.0;  // s, the largest |stamp - grid|
    bool regridded = false;   // the stamps were replaced by the grid (max_jitter above 1e-3 cycles)
};

// The receive-time jitter a capture's cycle stamps may have, in cycles: a lost cycle puts the stamps
// around it half a cycle or more off the fitted grid, beyond it.
constexpr double kCycleJitterTolerance = 0.4;

// Returns a table with columns `time_column`, position_columns[j] and torque_columns[j] (joint order of
// `joints`). Times are seconds from the first sample, on the capture's uniform grid when its stamps jitter
// within kCycleJitterTolerance (counts->max_jitter); a stamp beyond it (a lost cycle, a gap, a clock jump)
// or one that does not increase is an InputError naming the line.
CsvTable candump_joint_table(const std::vector<CandumpRecord>& records, const std::vector<hal::ProfileConfig>& joints,
                             const std::vector<std::string>& position_columns, const std::vector<std::string>& torque_columns,
                             const std::string& time_column, const std::string& source, CandumpJointCounts* counts = nullptr);

// One `candump -L` line for a frame ("(1700000000.000000) can0 123#DEADBEEF"), for writers of captures.
std::string format_candump_line(const hal::CanFrame& frame, const std::string& interface);

}  // namespace jacobid::io
