// SPDX-License-Identifier: MIT
#pragma once
// diagnose --export-robot FILE (docs/diagnose.md, "Exporting the improved description"): the robot description
// diagnose was given, with the effects it named added as the description's own model options, so that
// `identify --robot FILE` identifies the improved model (the discrepancy workflow's loop, closed in files).
//
//   coulomb_offset     -> friction: offset: true         (FOFFj on every joint)
//   rotor_inertia      -> rotor_inertia: true
//   presliding         -> friction: presliding: dahl      (x_p: the description's choice; auto chooses per joint)
//   coulomb_load       -> friction: coulomb_load: abs
//   coulomb_smoothing  -> friction: alpha: the named alpha' on that joint (a fixed alpha; with auto, identify
//                         chooses each joint's on held-out data, which is what the candidate found)
// Effects the description has no option for (torque_delay: identify --torque-delay; stribeck,
// coulomb_asymmetry, viscous_nonlinear, cogging, gravity) are listed with why, not dropped silently.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "diagnose/diagnosis.hpp"
#include "robot/robot_description.hpp"

namespace jacobid::diagnose {

struct ExportedDescription {
    robot::RobotDescription description;
    std::vector<std::string> added;                // e.g. "presliding (friction: presliding: dahl)"
    std::vector<std::string> not_in_description;   // e.g. "torque_delay 0.002 s: use identify --torque-delay 0.002"
    std::string yaml;                              // the file's text
    nlohmann::json summary;                        // JSON "export": {robot, added, not_in_description}
};

// `path`: where the file goes (a urdf model's URDF is named relative to it, so the file can be moved with it).
ExportedDescription export_diagnosed_robot(const robot::RobotDescription& description, const Diagnosis& diagnosis, const std::string& path);

}  // namespace jacobid::diagnose
