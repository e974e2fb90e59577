// SPDX-License-Identifier: MIT
#pragma once
// `jacobid payload --export-urdf F --export-robot F`: the estimated payload where other tools read it.
//   - a URDF fragment: a fixed <joint> from the last link to a `payload` <link> at the output frame, whose
//     <inertial> holds the mass, centre of mass and inertia about it (to paste into the robot's URDF);
//   - the arm's robot description with the payload's ten standard parameters added to the last link's (a payload
//     fixed to the last link is part of that body: docs/method.md, "Payload identification"), the YAML
//     `simulate`, `excite` and `diagnose` load (as identify --export-robot writes the arm).
#include <string>

#include "payload/arm_file.hpp"
#include "payload/payload_estimate.hpp"

namespace jacobid::payload {

// The link the payload is fixed to: for a URDF robot the last moving joint's child link, else "link<n>".
std::string last_link_name(const robot::RobotDescription& description);

std::string urdf_fragment(const PayloadEstimate& e, const robot::RobotDescription& description);

// The arm's description with `standard` (about the last link's frame) added to the last link's parameters.
robot::RobotDescription with_payload(const ArmModel& arm, const Standard10& standard);

}  // namespace jacobid::payload
