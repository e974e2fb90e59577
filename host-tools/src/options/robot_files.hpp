// SPDX-License-Identifier: MIT
#pragma once
// The files a robot description is read from, as inputs for the output guard (check_outputs,
// options/output_file.hpp): the description itself and, for model urdf, the URDF it names. An output written
// over either would destroy the robot it describes (issue 36: --export-urdf through a link to the URDF).
#include <string>
#include <vector>

#include "options/output_file.hpp"
#include "robot/robot_description.hpp"

namespace jacobid::options {

// `option`: the option that named the description ("--robot"); `path`: as given (empty: the built-in robot).
inline std::vector<NamedPath> robot_files(const std::string& option, const std::string& path, const robot::RobotDescription& description) {
    std::vector<NamedPath> files{{option, path}};
    if (!description.urdf.empty()) files.push_back({"the urdf: of " + option + " " + path, description.urdf});
    return files;
}

}  // namespace jacobid::options
