// SPDX-License-Identifier: MIT
#pragma once
// The JSON description of one designed kernel (`jacobid kernel --format json`: parameters, taps, delay,
// cutoff, weights oldest first), shared with the Python module's jacobid.kernel() so both give one layout.
#include <nlohmann/json.hpp>
#include <vector>

#include "jacobid/kernel_params.hpp"

namespace jacobid::options {

nlohmann::json describe_kernel(const KernelParams& params, const std::vector<double>& weights);

}  // namespace jacobid::options
