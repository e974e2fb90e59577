// SPDX-License-Identifier: MIT
#pragma once
// fw.yaml `monitor:` files -> the controller's MonitorModel (docs/firmware.md, "Contact monitor"): the robot
// description `identify --export-robot` wrote and the monitor YAML `jacobid monitor calibrate` wrote, read
// by the same readers `jacobid monitor` uses (monitor_model.hpp, monitor_file.hpp), so that the controller
// runs the model and thresholds the host replayed. Start-up only (allocates, throws).
#include <string>
#include <vector>

#include "jacobid/fwconfig/firmware_config.hpp"

namespace jacobid::monitor {

struct FirmwareMonitorLoad {
    firmware::MonitorModel model;
    std::vector<std::string> notes;  // what the operator should know (printed as warnings by jacobid-fw)
};

// InputError naming the file (and line, key) for an unreadable or unsuitable file: another joint count than
// fw.yaml's, a residual estimator (the controller runs the momentum observer), a model the monitor cannot run.
FirmwareMonitorLoad load_firmware_monitor(const firmware::FirmwareConfig& config);

}  // namespace jacobid::monitor
