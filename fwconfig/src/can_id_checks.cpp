// SPDX-License-Identifier: MIT
#include "can_id_checks.hpp"

#include <fmt/core.h>

#include <array>

#include "jacobid/fwconfig/firmware_config_yaml.hpp"
#include "jacobid/hal/joint_decoder_set.hpp"
#include "jacobid/hal/profile_registry.hpp"
#include "jacobid/yaml/yaml_section.hpp"

namespace jacobid::firmware {
namespace {

// The ids a joint's entry states ("motor_id: 1, reply_id: 0"), to name what two joints share.
std::string stated_ids(const YAML::Node& joint) {
    std::string ids;
    for (const auto& kv : joint) {
        const std::string key = kv.first.Scalar();
        if (key.size() > 3 && key.compare(key.size() - 3, 3, "_id") == 0 && kv.second.IsScalar()) {
            ids += (ids.empty() ? "" : ", ") + key + ": " + kv.second.Scalar();
        }
    }
    return ids.empty() ? "the default ids" : ids;
}

// The decoder set of the configured joints (false: the HAL refuses them; read_joint has named why).
bool configure_decoders(const std::vector<JointConfig>& configs, hal::JointDecoderSet<kMaxJoints>& set) {
    std::vector<hal::ProfileConfig> decoders;
    for (const JointConfig& j : configs) decoders.push_back(j.decoder);
    return set.configure(Span<const hal::ProfileConfig>(decoders.data(), decoders.size())).status == hal::ConfigStatus::Ok;
}

// Which of a joint's frames uses the standard id `id`: "command" (either mode), "telemetry", or "".
const char* frames_on(const hal::ProfileConfig& joint, std::uint32_t id) {
    auto on_id = [id](const hal::CanFrame* frames, std::size_t count) {
        for (std::size_t f = 0; f < count; ++f) {
            if (!frames[f].extended() && frames[f].id == id) return true;
        }
        return false;
    };
    std::array<hal::CanFrame, hal::kMaxCommandFrames> commands{};
    for (const hal::CommandMode mode : {hal::CommandMode::Position, hal::CommandMode::Torque}) {
        if (on_id(commands.data(), hal::encode_command(joint, hal::JointCommand{mode, 0.0, 0.0, 0.0, 0.0, 0.0}, commands.data()))) return "command";
    }
    std::array<hal::CanFrame, hal::kMaxTelemetryFrames> telemetry{};
    if (on_id(telemetry.data(), hal::encode_telemetry(joint, 0.0, 0.0, 0.0, telemetry.data()))) return "telemetry";
    return "";
}

}  // namespace

// Two joints listening to one device would each take the other's frames (the first joint in the list
// takes them all, and a capture reads as "a frame was lost"): every joint's own telemetry frames must
// reach its decoder, which is the decoders' own test (NotMine), so no profile's ids are named here.
void require_distinct_devices(const std::string& source, const YAML::Node& joints, const std::vector<JointConfig>& configs) {
    hal::JointDecoderSet<kMaxJoints> set;
    if (!configure_decoders(configs, set)) return;
    for (std::size_t j = 0; j < configs.size(); ++j) {
        std::array<hal::CanFrame, hal::kMaxTelemetryFrames> frames{};
        const std::size_t count = hal::encode_telemetry(configs[j].decoder, 0.0, 0.0, 0.0, frames.data());
        for (std::size_t f = 0; f < count; ++f) {
            const hal::RouteResult r = set.route(frames[f]);
            if (r.joint == hal::RouteResult::kNoJoint || r.joint == j) continue;
            throw ConfigError(fmt::format("{}: joints[{}] ({}) and joints[{}] ({}) listen to the same device (CAN id 0x{:X}; {} and {}): joints[{}] "
                                          "would take every frame of joints[{}]; give each joint its own id",
                                          yaml::where(source, joints[j]), r.joint, configs[r.joint].name, j, configs[j].name, frames[f].id,
                                          stated_ids(joints[r.joint]), stated_ids(joints[j]), r.joint, j));
        }
    }
}

void require_sync_id_unused(const std::string& source, const YAML::Node& sync_node, std::uint32_t sync_id, const YAML::Node& joints,
                            const std::vector<JointConfig>& configs) {
    hal::JointDecoderSet<kMaxJoints> set;
    if (!configure_decoders(configs, set)) return;
    hal::CanFrame sync{};
    sync.id = sync_id;
    const hal::RouteResult taken = set.route(sync);
    for (std::size_t j = 0; j < configs.size(); ++j) {
        std::string frames = frames_on(configs[j].decoder, sync_id);
        if (frames.empty() && taken.joint == j) frames = "telemetry";  // its decoder claims the SYNC frame
        if (frames.empty()) continue;
        throw ConfigError(fmt::format("{}: can.sync_id: 0x{:X} is also the CAN id of joints[{}] ({})'s {} frames ({}): the drives would take each "
                                      "SYNC for one of those frames and those frames for SYNCs; give can.sync_id an id no joint uses "
                                      "(0x80 by convention)",
                                      yaml::where(source, sync_node), sync_id, j, configs[j].name, frames, stated_ids(joints[j])));
    }
}

}  // namespace jacobid::firmware
