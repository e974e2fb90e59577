// SPDX-License-Identifier: MIT
#pragma once
// The drive-gain problem (drive_gains.hpp) with the physical constraints: every gain > 0, every link's
// pseudo-inertia and the payload's positive definite, rotor inertias and friction coefficients >= 0
// (physical_parametrization.hpp, constraint_blocks), solved by the interior point of lmi_barrier.hpp over
// [s; phi; g]: the robot's standard parameters s (the base ones are K s), the payload's ten parameters phi and
// the gains g. The cost is the least squares' weighted chi^2 plus, as identify --physical does, a small prior
// (weight PhysicalSettings' default) pulling the directions the logs do not see towards the description's
// inertials (the payload's unknown ones towards 0). The payload's known parameters are pinned by a stiff
// quadratic term (the solver takes linear matrix inequalities without a constant term, so the known mass
// cannot be a constant of the payload's block).
#include "identify/drive_gains/drive_gains.hpp"
#include "robot/robot_description.hpp"
#include "robot/serial_robot_model.hpp"

namespace jacobid::identify {

// estimator "constrained"; note: chi^2 against the least squares', Newton steps and duality gap.
DriveGainEstimate drive_gains_constrained(const DriveGainResult& result, const robot::SerialRobotModel& model,
                                          const robot::RobotDescription& description);

}  // namespace jacobid::identify
