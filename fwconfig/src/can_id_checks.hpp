// SPDX-License-Identifier: MIT
#pragma once
// CAN ids in fw.yaml that must not be shared: two joints on one device, and the SYNC frame on an id a joint
// uses. Each is decided by the profiles' own encoders and decoders (hal/profile_registry.hpp), so no
// profile's id scheme is named here.
#include <cstdint>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "jacobid/fwconfig/firmware_config.hpp"

namespace jacobid::firmware {

// Two joints listening to one device would each take the other's frames: every joint's own telemetry must
// reach its own decoder. Throws ConfigError naming both joints and their ids.
void require_distinct_devices(const std::string& source, const YAML::Node& joints, const std::vector<JointConfig>& configs);

// can.sync_id on the id of a joint's command frames (either command mode) or telemetry frames, or taken by a
// joint's decoder: the drive would take each SYNC for a command (or its replies would be SYNCs to the
// others). Throws ConfigError at `sync_node` naming can.sync_id and the joint's id keys.
void require_sync_id_unused(const std::string& source, const YAML::Node& sync_node, std::uint32_t sync_id, const YAML::Node& joints,
                            const std::vector<JointConfig>& configs);

}  // namespace jacobid::firmware
