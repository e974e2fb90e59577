// SPDX-License-Identifier: MIT
#pragma once
// A run that fails half-way (a diverging simulation, a full disk) removes its partial output, so that no
// partial log is left as if it were complete. Only a regular file is removed: an output given as a device
// (`-o /dev/null`, `-o /dev/full`) or a link is left alone; run as root, std::remove deleted /dev/full.
#include <filesystem>
#include <string>
#include <system_error>

namespace jacobid::io {

inline void remove_partial_output(const std::string& path) {
    std::error_code ec;
    if (std::filesystem::is_regular_file(std::filesystem::symlink_status(path, ec))) std::filesystem::remove(path, ec);
}

}  // namespace jacobid::io
