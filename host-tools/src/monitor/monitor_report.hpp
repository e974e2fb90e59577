// SPDX-License-Identifier: MIT
#pragma once
// What `jacobid monitor` prints (docs/monitor.md): the contact events as a table and as JSON, and a PNG of
// every joint's external-torque estimate with the threshold it was compared with and the events shaded.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "monitor/calibration.hpp"
#include "monitor/contact_events.hpp"
#include "monitor/monitor_file.hpp"

namespace jacobid::monitor {

std::string events_text(const std::vector<ContactEvent>& events, const Replay& replay, const robot::RobotDescription& robot);
nlohmann::json events_json(const std::vector<ContactEvent>& events, const Replay& replay, const MonitorFile& monitor,
                           const robot::RobotDescription& robot, const std::string& log);
void plot_events(const std::string& png, const std::vector<ContactEvent>& events, const Replay& replay, const MonitorFile& monitor,
                 const robot::RobotDescription& robot, const std::string& title);

// CSV t, tau_ext1.., threshold1.. (the threshold each sample was compared with).
std::string estimates_csv(const Replay& replay, const MonitorFile& monitor);

std::string calibration_text(const std::vector<JointCalibration>& joints, const MonitorFile& monitor, const robot::RobotDescription& robot);
nlohmann::json calibration_json(const std::vector<JointCalibration>& joints, const MonitorFile& monitor);

}  // namespace jacobid::monitor
