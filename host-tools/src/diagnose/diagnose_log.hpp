// SPDX-License-Identifier: MIT
#pragma once
// One log diagnosed as `jacobid diagnose` does it: friction alpha: auto chosen on the identification log (as
// identify does), then the search for missing effects (run_diagnosis), the joint names and the smoothing's
// note filled in. Shared by the command and the Python module's jacobid.diagnose().
#include <functional>
#include <string>
#include <vector>

#include "diagnose/diagnosis.hpp"
#include "identify/plan/log_columns.hpp"
#include "robot/robot_description.hpp"
#include "robot/robot_model.hpp"

namespace jacobid::diagnose {

Diagnosis diagnose_log(const robot::RobotDescription& robot, const robot::RobotModel& model, const identify::LogColumns& log,
                       const identify::LogColumns* validation, const DiagnoseSettings& settings,
                       const std::function<void(const std::string&)>& progress);
// Several logs together (diagnose --in a.csv --in b.csv; run_diagnosis): friction alpha: auto chosen on the
// longest, with the choices imposed on every log, as identify does with several logs.
Diagnosis diagnose_log(const robot::RobotDescription& robot, const robot::RobotModel& model, const std::vector<identify::LogColumns>& logs,
                       const identify::LogColumns* validation, const DiagnoseSettings& settings,
                       const std::function<void(const std::string&)>& progress);

}  // namespace jacobid::diagnose
