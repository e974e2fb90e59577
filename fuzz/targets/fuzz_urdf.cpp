// SPDX-License-Identifier: MIT
// URDF robot descriptions (host-tools/src/robot/urdf_chain.*, through urdfdom), the text behind
// `model: urdf` in a robot description. Bad input must be an InputError, never another exception or a crash.
// Properties of an accepted URDF: one name and one limit pair per moving joint, finite joint geometry that
// the kinematic chain accepts (antecedent order, unit axis, proper rotation), finite standard parameters;
// and the robot description that points at it builds a model with that many joints.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>

#include "core/errors.hpp"
#include "fuzz_check.hpp"
#include "scratch_directory.hpp"
#include "jacobid/robot/kinematic_chain.hpp"
#include "robot/robot_description.hpp"
#include "robot/urdf_chain.hpp"

using namespace jacobid;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string xml(reinterpret_cast<const char*>(data), size);
    robot::UrdfChain chain;
    try {
        chain = robot::parse_urdf_chain(xml, "fuzz.urdf");
    } catch (const InputError&) {
        return 0;
    }
    const std::size_t n = chain.joints.size();
    JACOBID_FUZZ_CHECK(n >= 1 && chain.names.size() == n && chain.limits.size() == n, "joints, names and limits differ in number");
    robot::KinematicChain<64> kinematics;
    for (std::size_t j = 0; j < n && j < 64; ++j) {
        JACOBID_FUZZ_CHECK(kinematics.add(chain.joints[j]) == robot::ChainError::Ok, "a parsed joint is not a valid chain joint");
        JACOBID_FUZZ_CHECK(!(chain.limits[j].first > chain.limits[j].second), "joint limits lower > upper");
    }
    for (const auto& [name, value] : chain.standard_parameters) JACOBID_FUZZ_CHECK(std::isfinite(value), "non-finite standard parameter");

    // The same text as a file behind `model: urdf`: description and model.
    const std::filesystem::path urdf = fuzz::scratch_directory("urdf") / "robot.urdf";
    std::ofstream(urdf, std::ios::binary) << xml;
    try {
        const robot::RobotDescription d =
            robot::parse_robot_description("model: urdf\nurdf: " + urdf.string() + "\n", (fuzz::scratch_directory("urdf") / "robot.yaml").string());
        const std::unique_ptr<robot::RobotModel> model = robot::make_robot_model(d);
        JACOBID_FUZZ_CHECK(model != nullptr && static_cast<std::size_t>(model->joint_count()) == n, "model joint count differs from the URDF");
    } catch (const InputError&) {
        // e.g. more moving joints than the serial model supports: a message, not a model.
    }
    return 0;
}
