// SPDX-License-Identifier: MIT
#pragma once
// `--validate` on one continuous log, shared by `jacobid identify` (without --on-gap split) and the Python
// module's identify(validate=...): the gravity check when the log holds a pose (static_validation.hpp), else
// the torques predicted through the identification's differentiators and F_p with its torque delay applied
// (validation.hpp).
#include "identify/pipeline/pipeline.hpp"
#include "identify/report/report.hpp"
#include "robot/robot_model.hpp"

namespace jacobid::identify {

// Fills r.static_validation or r.validation from `log`, with the identified parameters r.solution.x.
// `settings` are the identification's; min_joint_motion decides whether the log holds a pose.
void validate_log(const robot::RobotModel& model, const LogColumns& log, const PipelineSettings& settings, double min_joint_motion,
                  MethodResult& r);

}  // namespace jacobid::identify
