// SPDX-License-Identifier: MIT
#pragma once
// The smallest motion a planned trajectory may give a joint: 1 mrad (or 1 mm for a prismatic joint). Below
// it the encoder steps and the torque noise of a real robot see nothing, so limits that allow no more make a
// design or a simulation meaningless (issue 36: excite --velocity-limit 1e-9 "designed" a 1e-10 rad motion;
// simulate --velocity-limit 1e-308 logged a robot standing still). Shared by excite (excite/design_checks.hpp)
// and the simulator's random moves (sim::validate).
namespace jacobid {

inline constexpr double kMinMeasurableMotion = 1e-3;

}  // namespace jacobid
