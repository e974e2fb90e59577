// SPDX-License-Identifier: MIT
#pragma once
// Where the tests find the shared real robot logs (../shared/realdata: UR10e and pendubot recordings, never
// copied into the repository) and the log formats that read them, and the skip when they are absent.
// A test that includes this header is compiled with JACOBID_REALDATA_DIR (the configured folder,
// tests/integration/CMakeLists.txt) and JACOBID_SOURCE_DIR defined.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

namespace jacobid::test {

// The environment variable of the same name overrides the configured folder (e.g. to check the skip).
inline std::filesystem::path realdata_dir() {
    const char* env = std::getenv("JACOBID_REALDATA_DIR");
    return env ? std::filesystem::path(env) : std::filesystem::path(JACOBID_REALDATA_DIR);
}

// examples/formats/: the --log-format files of the shared logs.
inline std::filesystem::path log_formats_dir() { return std::filesystem::path(JACOBID_SOURCE_DIR) / "examples" / "formats"; }

// The logs a test runs "on every log" of a family: all of them, or only the first when
// JACOBID_REALDATA_ONE_PER_FAMILY=1. scripts/sanitize-test.sh sets it: under ASan + UBSan the same code runs
// 5-8x slower, and one log of a family reaches the code paths the others do (the native suite runs them all).
inline std::vector<std::filesystem::path> every_or_first(std::vector<std::filesystem::path> logs) {
    const char* env = std::getenv("JACOBID_REALDATA_ONE_PER_FAMILY");
    if (env && std::string(env) == "1" && logs.size() > 1) logs.resize(1);
    return logs;
}

}  // namespace jacobid::test

// Skips the calling test, with the reason, when the shared logs are absent.
#define REQUIRE_REALDATA()                                                                                                        \
    if (!std::filesystem::exists(::jacobid::test::realdata_dir() / "README.md"))                                                  \
    GTEST_SKIP() << "shared real logs not found at " << ::jacobid::test::realdata_dir()                                           \
                 << " (configure with -DJACOBID_REALDATA_DIR=... or set it in the environment); test skipped"
