// SPDX-License-Identifier: MIT
#pragma once
// `--base-frequency auto` and `--harmonics auto` (docs/excite.md, "Frequency content from the limits"):
//   - the period: the duration split into P periods, P the smallest whole number >= 2 whose period is at most
//     kMaxPeriod (10 s), then fewer (down to 2) while a period holds fewer than kMinHarmonics harmonics below
//     F_top: at least two periods, so that identify --period can average them and take the noise from their
//     spread; no period longer than needed; but enough harmonics for a slow robot (the UR10e's shared log's limits,
//     F_top 0.3 Hz: 2 x 25 s with 7 harmonics instead of 5 x 10 s with 3);
//   - the harmonics: up to the highest frequency at which a joint can still reach its velocity limit v within
//     its acceleration limit a (a harmonic of frequency F and velocity amplitude v has acceleration 2 pi F v):
//     F_top = max over joints of a_j / (2 pi v_j), within [kMinTop, kMaxTop] (0.3 .. 2 Hz: the identification
//     bandwidth, which sets F_p at 5 x and the differentiators at 10 x, stays where encoder noise is harmless);
//     without both limits on a joint, F_top = kDefaultTop (0.5 Hz). L = floor(F_top / f), within [3, kMaxHarmonics].
#include <string>
#include <vector>

#include "excite/excitation_problem.hpp"

namespace jacobid::excite {

inline constexpr double kMaxPeriod = 10.0;   // s
inline constexpr double kMinTop = 0.3, kMaxTop = 2.0, kDefaultTop = 0.5;  // Hz
inline constexpr int kMaxHarmonics = 10;
inline constexpr int kMinHarmonics = 6;

double auto_base_frequency(double duration, const std::vector<JointLimits>& limits);
// F_top (Hz) of the rule above.
double top_frequency(const std::vector<JointLimits>& limits);
int auto_harmonics(double base_frequency, const std::vector<JointLimits>& limits);

}  // namespace jacobid::excite
