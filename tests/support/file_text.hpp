// SPDX-License-Identifier: MIT
#pragma once
// A whole file as a string (empty when it cannot be read): for the test helpers that keep results in files.
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace jacobid::test {

inline std::string file_text(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

}  // namespace jacobid::test
