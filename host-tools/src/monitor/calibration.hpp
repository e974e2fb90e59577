// SPDX-License-Identifier: MIT
#pragma once
// Thresholds from contact-free logs (docs/monitor.md, "Calibration"): per joint, over every sample of every
// log, the (1 - a) quantile of |tau_ext| while the joint moves, and of the excess beyond the Coulomb band
// max(|tau_ext| - band, 0) while it stands, times (1 + margin). a is the stated per-sample false-alarm rate:
// on the calibration logs themselves at most a fraction a of a joint's samples exceed the quantile, and the
// margin covers the logs not seen. With fewer than 1/a samples the quantile is the largest value seen.
#include <string>
#include <vector>

#include "jacobid/robot/contact_detector.hpp"
#include "monitor/external_torque_replay.hpp"

namespace jacobid::monitor {

struct JointCalibration {
    robot::JointThresholds thresholds;
    std::size_t moving_samples = 0, standing_samples = 0;
    double max_band = 0.0;  // N.m: the largest Coulomb band seen at standstill
    std::string note;       // when a state had no samples and its threshold was derived from the other
};

std::vector<JointCalibration> calibrate(const std::vector<Replay>& replays, double false_alarm_rate, double margin);

}  // namespace jacobid::monitor
