// SPDX-License-Identifier: MIT
#pragma once
// The monitor YAML `jacobid monitor calibrate` writes and `jacobid monitor` reads (docs/monitor.md):
//
//   robot: identified.yaml          # the description it was calibrated with (informative)
//   estimator: {type: observer, gain: 100, velocity_window: 0.02, acceleration_window: 0.04, measured_velocity: true}
//   standing_velocity: 0.02         # rad/s: a joint slower than this ...
//   standing_time: 0.1              # s: ... for this long stands (one value or one per joint)
//   band_margin: 0.2                # a standing joint's band is (1 + band_margin) x its Coulomb level (optional, 0;
//                                   # one value or one per joint)
//   false_alarm_rate: 1e-4          # per sample, the calibration's (1 - a) quantile
//   margin: 0.25                    # thresholds = (1 + margin) x quantile
//   hold: 0.05                      # s: an event ends this long after its last sample in contact
//   confirm: 1                      # consecutive samples in contact before an event starts
//   joints:                         # N.m: moving, and beyond the Coulomb band when standing
//     - {moving: 1.2, standing: 0.4}
//   calibrated_from: [a.csv, b.csv]
//
// Errors are InputError "file:line:column: key: what was expected".
#include <string>
#include <vector>

#include "jacobid/robot/contact_detector.hpp"
#include "monitor/external_torque_replay.hpp"

namespace jacobid::monitor {

struct MonitorFile {
    std::string robot;
    EstimatorSettings estimator;
    std::vector<double> standing_velocity{0.02};
    double standing_time = 0.1;  // s below the standing velocity before a joint stands
    std::vector<double> band_margin{0.0};  // a standing joint's band is (1 + band_margin) x its Coulomb level (break-away); one or one per joint
    double false_alarm_rate = 1e-4;
    double margin = 0.25;
    double hold = 0.05;
    int confirm = 1;  // consecutive samples in contact before an event starts
    std::vector<robot::JointThresholds> thresholds;
    std::vector<std::string> calibrated_from;
};

MonitorFile parse_monitor_file(const std::string& yaml_text, const std::string& source, std::size_t joints);
MonitorFile load_monitor_file(const std::string& path, std::size_t joints);
std::string to_yaml(const MonitorFile& file);

}  // namespace jacobid::monitor
