// SPDX-License-Identifier: MIT
#pragma once
// A robot description whose last link carries a payload (mass, centre of mass and inertia about it, in the last
// link's frame): the payload's ten standard parameters added to that link's (parallel axes), as a rigid payload
// is part of the body (docs/method.md, "Payload identification"). The simulated truth of the drive-gain
// and payload tests.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include "robot/robot_description.hpp"

namespace jacobid::test {

// The payload of docs/identify.md, "Payload" (the truth of the payload tests and of excite --payload's), in link 6's
// frame (the UR5-like flange): 1.5 kg, centre of mass 3 cm and 2 cm off the flange axis.
constexpr double kDocsPayloadMass = 1.5;
inline Eigen::Vector3d docs_payload_com() { return {0.03, -0.02, 0.05}; }
inline Eigen::Matrix3d docs_payload_central_inertia() {
    Eigen::Matrix3d i;
    i << 4e-3, 5e-4, -3e-4, 5e-4, 6e-3, 2e-4, -3e-4, 2e-4, 3e-3;
    return i;
}

// Writes dir/loaded.yaml: `robot` (whose last link, number `link`, lists its ten inertial parameters) with the payload.
inline std::string write_loaded_robot(const std::string& robot, const std::filesystem::path& dir, int link, double m, const Eigen::Vector3d& c,
                                      const Eigen::Matrix3d& central) {
    jacobid::robot::RobotDescription d = jacobid::robot::load_robot_description(robot);
    const Eigen::Matrix3d io = central + m * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
    const std::string n = std::to_string(link);
    const std::map<std::string, double> add = {{"XX" + n, io(0, 0)}, {"XY" + n, io(0, 1)}, {"XZ" + n, io(0, 2)}, {"YY" + n, io(1, 1)},
                                               {"YZ" + n, io(1, 2)}, {"ZZ" + n, io(2, 2)}, {"MX" + n, m * c.x()}, {"MY" + n, m * c.y()},
                                               {"MZ" + n, m * c.z()}, {"M" + n, m}};
    std::size_t found = 0;
    for (auto& [name, value] : d.parameters) {
        const auto it = add.find(name);
        if (it == add.end()) continue;
        value += it->second;
        ++found;
    }
    EXPECT_EQ(found, add.size()) << robot << " no longer lists link " << link << "'s ten inertial parameters";
    std::filesystem::create_directories(dir);
    const std::string path = (dir / "loaded.yaml").string();
    std::ofstream out(path);
    out << jacobid::robot::to_yaml(d);
    out.close();
    EXPECT_TRUE(out.good()) << "could not write " << path;
    return path;
}

}  // namespace jacobid::test
