// SPDX-License-Identifier: MIT
#pragma once
// What the excite tests share: the command line, the planar 2R they design for, and their scratch files.
#include <filesystem>
#include <string>

#include "scratch_directory.hpp"

namespace jacobid::test {

inline const std::string kJacobid = JACOBID_EXECUTABLE;
inline const std::string kTwoLink = std::string(JACOBID_SOURCE_DIR) + "/examples/robots/planar2r_mdh.yaml";

// A file `name` in the test's own scratch folder `folder` (created).
inline std::string excite_scratch(const std::string& folder, const std::string& name) {
    const std::filesystem::path dir = scratch_directory() / folder;
    std::filesystem::create_directories(dir);
    return (dir / name).string();
}

}  // namespace jacobid::test
