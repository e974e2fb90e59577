// SPDX-License-Identifier: MIT
#pragma once
// The configuration keys every profile shares (the link-side JointMapping), read through any `Fields`
// object with the YamlSection interface (yaml/include/jacobid/yaml/yaml_section.hpp): number(key,
// fallback), positive(key, fallback), fail(key, message). A template keeps the HAL free of yaml-cpp (it
// builds for boards); the firmware passes its YamlSection (docs/profiles.md, "The registry").
#include "jacobid/hal/joint_state.hpp"

namespace jacobid::hal {

template <typename Fields>
JointMapping read_mapping(Fields& s, JointMapping m) {
    m.gear_ratio = s.number("gear_ratio", m.gear_ratio);
    m.direction = s.number("direction", m.direction);
    if (m.direction != 1.0 && m.direction != -1.0) s.fail("direction", "must be 1 or -1");
    m.position_offset = s.number("offset", m.position_offset);
    m.torque_constant = s.number("torque_constant", m.torque_constant);
    m.max_abs_velocity = s.positive("max_velocity", m.max_abs_velocity);
    m.max_abs_torque = s.positive("max_torque", m.max_abs_torque);
    return m;
}

// The shared key a mapping status is about, or nullptr when the status is the profile's own.
inline const char* mapping_key_of(ConfigStatus s) noexcept {
    switch (s) {
        case ConfigStatus::InvalidGearRatio: return "gear_ratio";
        case ConfigStatus::GearRatioOutOfRange: return "gear_ratio";
        case ConfigStatus::InvalidOffset: return "offset";
        case ConfigStatus::InvalidDirection: return "direction";
        case ConfigStatus::InvalidTorqueConstant: return "torque_constant";
        case ConfigStatus::InvalidLimits: return "max_torque";
        default: return nullptr;
    }
}

}  // namespace jacobid::hal
