// SPDX-License-Identifier: MIT
#pragma once
// The table trajectory playback reads at start-up: `jacobid excite`'s CSV (a header naming t, q1..qn,
// qd1..qn, optionally qdd1..qn and tau1..tau_n; one row per control cycle from t = 0). Errors are
// ConfigError lines naming the file, the line and the column.
#include <string>
#include <vector>

#include "jacobid/fwconfig/playback_config.hpp"

namespace jacobid::firmware {

// `torques`: the tau columns are required (torque-mode playback) rather than optional feed-forward.
std::vector<TrajectoryRow> load_trajectory_table(const std::string& path, std::size_t joints, double rate, bool torques);

}  // namespace jacobid::firmware
