// SPDX-License-Identifier: MIT
#pragma once
// `jacobid payload`'s text table and JSON (payload_estimate.hpp).
#include <nlohmann/json.hpp>
#include <string>

#include "payload/payload_estimate.hpp"

namespace jacobid::payload {

std::string payload_text(const PayloadEstimate& e);
nlohmann::json payload_json(const PayloadEstimate& e);

}  // namespace jacobid::payload
