// SPDX-License-Identifier: MIT
#pragma once
// The position controller of a robot description (`controller:`), the loop the estimators IDIM-IV and
// DIDIM simulate the identified model in (docs/method.md, "Estimators"), and that `jacobid simulate` runs:
//
//   controller: {kp: [900, 300], kd: [60, 20], rate: 1000}   # PD gains per joint (N.m/rad, N.m s/rad), Hz
//   controller: {omega: 30, damping: 1, rate: 1000}          # or gains from a loop bandwidth (rad/s):
//                                                            # Kp = M_jj(q0) omega^2, Kd = 2 zeta M_jj(q0) omega
//   substeps: 5 (optional, both forms): RK4 steps per control period of the simulation.
//
// q0 is the simulator's start configuration (each joint at 0 clamped to its limits) and M the inertia
// matrix of the description's true parameters, so that the gains are those `jacobid simulate --omega-dyn`
// computes.
#include <Eigen/Core>
#include <string>
#include <vector>

namespace YAML {
class Emitter;
class Node;
}  // namespace YAML

namespace jacobid::robot {

struct ControllerDescription {
    std::vector<double> kp, kd;  // explicit gains, one per joint; empty: from omega
    double omega = 0.0;          // rad/s (when kp is empty)
    double damping = 1.0;
    double rate = 1000.0;        // Hz
    int substeps = 5;
};

// Reads the `controller` map (node) of `source` for a robot of `joints` joints. InputError
// "file:line:column: controller.key: ..." for an unknown key, a missing or malformed one.
ControllerDescription parse_controller(const std::string& source, const YAML::Node& node, std::size_t joints);
void write_controller(YAML::Emitter& out, const ControllerDescription& controller);

}  // namespace jacobid::robot
