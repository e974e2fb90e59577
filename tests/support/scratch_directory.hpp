// SPDX-License-Identifier: MIT
#pragma once
// A per-process scratch folder for tests that write files, removed when the test program exits.
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>
#include <unistd.h>

namespace jacobid::test {

inline const std::filesystem::path& scratch_directory() {
    struct Folder {
        std::filesystem::path path;
        Folder() : path(std::filesystem::temp_directory_path() / ("jacobid-test-" + std::to_string(::getpid()))) {
            std::filesystem::create_directories(path);
        }
        ~Folder() {
            std::error_code ec;
            std::filesystem::remove_all(path, ec);
        }
    };
    static const Folder folder;
    return folder.path;
}

// DIR/folder/name in the scratch directory, the folder created.
inline std::filesystem::path scratch_file(const std::string& folder, const std::string& name) {
    const std::filesystem::path dir = scratch_directory() / folder;
    std::filesystem::create_directories(dir);
    return dir / name;
}

// Writes `text` (bytes as given) to scratch_file(folder, name); returns its path.
inline std::string write_scratch_file(const std::string& folder, const std::string& name, const std::string& text) {
    const std::filesystem::path p = scratch_file(folder, name);
    std::ofstream(p, std::ios::binary) << text;
    return p.string();
}

}  // namespace jacobid::test
