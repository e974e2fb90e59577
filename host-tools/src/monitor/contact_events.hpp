// SPDX-License-Identifier: MIT
#pragma once
// Contact events from a replayed log (docs/monitor.md): each sample is judged by the lib's ContactDetector
// (contact_detector.hpp: moving threshold, or the Coulomb band plus the standing threshold); an event starts
// at the first sample in contact and ends at the last one before `hold` seconds without any joint in
// contact, so that one push that dips under its threshold for a sample is one event. An event starts once the
// contact is confirmed (`confirm` consecutive samples).
#include <vector>

#include "jacobid/robot/contact_detector.hpp"
#include "monitor/external_torque_replay.hpp"

namespace jacobid::monitor {

struct ContactEvent {
    double start = 0.0, end = 0.0;  // s: first and last sample in contact (when the controller knows it)
    std::vector<int> joints;        // 0-based, every joint in contact at some sample of the event
    std::vector<double> peak;       // per joint of the robot: the external torque of largest magnitude within [start, end]
    std::vector<double> peak_time;  // s, per joint
    // Per joint: the median estimate over [start, end], the level of a held contact (a pulse's plateau: the
    // peak adds the noise's largest excursion to it, a mean the rise and the decay).
    std::vector<double> median;
};

// `confirm`: consecutive samples in contact before an event starts (ContactDetector::set_confirm); the
// event's start is the confirming sample, when a controller would act.
std::vector<ContactEvent> contact_events(const Replay& replay, const std::vector<robot::JointThresholds>& thresholds, double hold, int confirm = 1);

// The threshold each sample of joint j was compared with (for plots).
std::vector<double> applied_threshold(const Replay& replay, const robot::JointThresholds& thresholds, std::size_t joint);

}  // namespace jacobid::monitor
