// SPDX-License-Identifier: MIT
#pragma once
// What the CLI tests of bad input share: a file's text, and the check that a command refused its input the
// project's way (exit status 2, one "jacobid <command>: error: ..." line holding every key word).
#include <gtest/gtest.h>

#include <initializer_list>
#include <string>

#include "file_text.hpp"
#include "run_command.hpp"

namespace jacobid::test {

inline std::string read_text(const std::string& path) { return file_text(path); }

inline void expect_refused(const CommandResult& r, std::initializer_list<std::string> words) {
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find(": error: "), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("internal error"), std::string::npos) << r.err;
    for (const auto& w : words) EXPECT_NE(r.err.find(w), std::string::npos) << "missing '" << w << "' in: " << r.err;
}

}  // namespace jacobid::test
