// SPDX-License-Identifier: MIT
// Robot description YAML (host-tools/src/robot/robot_description.*), read by identify/simulate/diagnose.
// Any text must either parse or raise InputError (exit 2), never another exception or a crash.
// Properties of an accepted description: its model can be built (make_robot_model), the model's
// regressor has as many joints as the description, and the description written back as YAML (to_yaml)
// parses again to the same values.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

#include "core/errors.hpp"
#include "fuzz_check.hpp"
#include "robot/robot_description.hpp"

using namespace jacobid;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    robot::RobotDescription d;
    try {
        d = robot::parse_robot_description(text, "robot.yaml");
    } catch (const InputError&) {
        return 0;
    }
    std::unique_ptr<robot::RobotModel> model;
    try {
        model = robot::make_robot_model(d);
    } catch (const InputError&) {
        return 0;
    }
    JACOBID_FUZZ_CHECK(model != nullptr, "make_robot_model returned no model");
    JACOBID_FUZZ_CHECK(d.joints.empty() || model->joint_count() == static_cast<int>(d.joints.size()), "model and description joint counts differ");
    robot::RobotDescription again;
    try {
        again = robot::parse_robot_description(robot::to_yaml(d), "again.yaml");
    } catch (const InputError&) {
        JACOBID_FUZZ_CHECK(false, "to_yaml of an accepted description does not parse");
    }
    JACOBID_FUZZ_CHECK(again.model == d.model && again.L1 == d.L1 && again.joints.size() == d.joints.size() &&
                           again.friction_offset == d.friction_offset && again.rotor_inertia == d.rotor_inertia &&
                           again.parameters == d.parameters,
                       "to_yaml + parse changes the description");
    return 0;
}
