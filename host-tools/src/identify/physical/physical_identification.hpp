// SPDX-License-Identifier: MIT
#pragma once
// identify --physical / --semi-physical on an identified log: the least-squares solution replaced by the
// physically consistent one (physical_least_squares.hpp) over the same (weighted) equations, with the
// description's standard values (URDF/CAD inertials, `parameters`) as the prior. Validation, plots and the
// plausibility checks that follow then see the consistent parameters.
#include <nlohmann/json.hpp>
#include <string>

#include "identify/identify_run.hpp"
#include "identify/physical/physical_least_squares.hpp"
#include "robot/robot_description.hpp"

namespace jacobid::identify {

// InputError when the model has no standard parameters (planar2r: describe the robot as mdh or urdf).
// The solution's x, residual norms and violations become the consistent fit's; its standard deviations
// stay those of the unconstrained problem (a linearization that ignores active constraints).
void make_physically_consistent(IdentifiedLog& fit, const robot::RobotDescription& description, const robot::RobotModel& nominal,
                                PhysicalSettings settings);

// One line for the text report: the constraint, the cost over the unconstrained fit, the active constraints.
std::string describe(const PhysicalReport& report);
// JSON "physical": constraint, prior_weight, iterations, converged, duality_gap, seconds, data_cost, unconstrained_data_cost,
// cost_increase_percent, active, standard {name: value}, projected_standard {name: value}.
nlohmann::json physical_json(const PhysicalReport& report);

}  // namespace jacobid::identify
