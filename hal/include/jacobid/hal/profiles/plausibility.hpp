// SPDX-License-Identifier: MIT
#pragma once
// The last check every device profile applies to a decoded link-side value before it enters a JointState.
#include <cmath>

namespace jacobid::hal {

// Finite and within its plausibility limit. An infinite limit (the default) disables the limit but never
// the finiteness check: with extreme yet valid scalings (a gear ratio or torque constant near 1e308, a
// generic signal scale of 1e300) a finite field still overflows to infinity, which no joint reports.
inline bool plausible(double value, double limit) noexcept { return std::isfinite(value) && std::abs(value) <= limit; }

}  // namespace jacobid::hal
