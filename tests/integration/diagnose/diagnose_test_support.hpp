// SPDX-License-Identifier: MIT
#pragma once
// Shared by the diagnosis CLI tests: a 2R robot description, simulate/diagnose runs in the scratch folder.
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "run_command.hpp"
#include "scratch_directory.hpp"

namespace jacobid::test {

inline std::string diagnose_robot_yaml() {
    const std::string path = (scratch_directory() / "robot.yaml").string();
    std::ofstream(path) << "model: planar2r\nL1: 0.5\njoints:\n"
                           "  - {name: j1, position: q1, torque: tau1, limits: [-2.5, 2.5]}\n"
                           "  - {name: j2, position: q2, torque: tau2, limits: [-2.5, 2.5]}\n"
                           "friction: {coulomb: smooth, alpha: 100}\n";
    return path;
}

inline std::string scratch(const std::string& name) { return (scratch_directory() / name).string(); }

inline nlohmann::json read_json(const std::string& path) {
    std::ifstream in(path);
    nlohmann::json j;
    in >> j;
    return j;
}

// `jacobid simulate` with the paper's noise (0.05 / 0.01 N.m by default) and 2^16 counts/rev; extra options appended.
inline CommandResult simulate_log(const std::string& out, double duration, int seed, const std::string& extra,
                                  const std::string& noise = "0.05,0.01") {
    return run_command(std::string(JACOBID_EXECUTABLE) + " simulate --robot " + diagnose_robot_yaml() + " --out " + out + " --duration " +
                       std::to_string(duration) + " --torque-noise " + noise + " --seed " + std::to_string(seed) + " --noise-seed " +
                       std::to_string(seed + 1000) + " " + extra);
}

}  // namespace jacobid::test
