// SPDX-License-Identifier: MIT
#pragma once
// The one-paragraph account of an automatic bandwidth estimate that identify prints and writes into its JSON
// (settings.bandwidth_estimate.description): the band and what limited it, the torque's band, each joint's
// noise-floor share, the joints left out and the jumps ignored.
#include <string>
#include <vector>

#include "identify/plan/bandwidth.hpp"

namespace jacobid::identify {

// The moving joints whose `used` flag equals `used`, by name, comma-separated.
std::string moving_joint_names(const std::vector<JointBandwidth>& joints, bool used);

// `ratio`: the differentiator cutoff over the bandwidth.
std::string describe_bandwidth(const BandwidthEstimate& estimate, double ratio);

}  // namespace jacobid::identify
