// SPDX-License-Identifier: MIT
#pragma once
// Where a logged joint position may be: within the robot description's joint limits, give or take the
// joint's whole range (upper - lower) on each side. A position beyond that is an outlier (one cell of
// 50 rad where the limits are +-2.5 gave exit 0 and only a friction warning), refused with its line and
// column (issue 20). The margin is that wide because real logs pass their limits: the pendubot's passive
// joint turns to 9.2 rad beside URDF limits of +-6.28. Only limits the user gave are checked (a
// description's `limits:`, a URDF's <limit> of a non-continuous joint), never the defaults.
#include <string>

namespace jacobid::io {

struct PositionBounds {
    double lower = 0.0, upper = 0.0;  // the joint's limits (rad or m)
    std::string joint;                // "joint 1 (j1)", for messages
    double margin() const { return upper - lower; }
    bool holds(double q) const { return q >= lower - margin() && q <= upper + margin(); }
    // "value 50 is outside joint 1 (j1)'s limits [-2.5, 2.5] by more than their range 5 (an outlier?)"
    std::string refusal(double q) const;
};

}  // namespace jacobid::io
