// SPDX-License-Identifier: MIT
#pragma once
// A per-process scratch folder for tests that write files, removed when the test program exits.
#include <filesystem>
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

}  // namespace jacobid::test
