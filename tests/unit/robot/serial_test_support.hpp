// SPDX-License-Identifier: MIT
#pragma once
// Loading the published example robots (examples/robots/) for the serial-robot tests.
#include <string>

#include "core/errors.hpp"
#include "robot/robot_description.hpp"
#include "robot/serial_robot_model.hpp"

namespace jacobid::test {

inline std::string example_robot(const std::string& name) { return std::string(JACOBID_TESTS_DIR) + "/../examples/robots/" + name; }

inline robot::SerialRobotConfig serial_config(const robot::RobotDescription& d) {
    robot::SerialRobotConfig config;
    config.name = d.model;
    config.joints = d.chain;
    config.gravity = d.gravity;
    config.options.coulomb = d.coulomb;
    config.options.rotor_inertia = d.rotor_inertia;
    config.options.friction_offset = d.friction_offset;
    return config;
}

// The InputError message of parsing `yaml` as a robot description "r.yaml", or "no error".
inline std::string description_error_of(const std::string& yaml) {
    try {
        robot::parse_robot_description(yaml, "r.yaml");
    } catch (const InputError& e) {
        return e.what();
    }
    return "no error";
}

}  // namespace jacobid::test
