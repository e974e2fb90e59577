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
};

// Returns a table with columns `time_column`, position_columns[j] and torque_columns[j] (joint order of
// `joints`). Times are seconds from the first sample.
CsvTable candump_joint_table(const std::vector<CandumpRecord>& records, const std::vector<hal::ProfileConfig>& joints,
                             const std::vector<std::string>& position_columns, const std::vector<std::string>& torque_columns,
                             const std::string& time_column, const std::string& source, CandumpJointCounts* counts = nullptr);

// One `candump -L` line for a frame ("(1700000000.000000) can0 123#DEADBEEF"), for writers of captures.
std::string format_candump_line(const hal::CanFrame& frame, const std::string& interface);

}  // namespace jacobid::io
