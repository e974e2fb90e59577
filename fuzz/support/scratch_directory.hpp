// SPDX-License-Identifier: MIT
#pragma once
// A directory of this fuzzing process for targets whose parser reads or writes files (removed and
// recreated by the target as it needs; one per process, so parallel jobs do not share files).
#include <unistd.h>

#include <filesystem>
#include <string>

namespace jacobid::fuzz {

inline const std::filesystem::path& scratch_directory(const std::string& target) {
    static const std::filesystem::path dir = [&target] {
        auto p = std::filesystem::temp_directory_path() / ("jacobid-fuzz-" + target + "-" + std::to_string(getpid()));
        std::filesystem::create_directories(p);
        return p;
    }();
    return dir;
}

}  // namespace jacobid::fuzz
