// SPDX-License-Identifier: MIT
#pragma once
// `jacobid simulate` made once per run for every test case that asks for the same log (command_cache.hpp):
// gtest_discover_tests gives each case its own process and scratch folder, so the cases of a suite that
// share a log used to simulate it again each (a 60 s 2R log costs ~4 s of CPU under ASan, and the sanitizer
// stage runs hundreds of such cases). The cache key is the command with the scratch folder left out, the
// jacobid executable, and the contents of every file the arguments name that exists when asked (the robot
// description, a trajectory, a log format): a case with another description gets its own simulation.
//
// The simulator is fixture_executable()'s (command_cache.hpp): in the sanitizer run, the native build's.
//
// The log and what simulate writes beside it (`<stem>.truth.json`, and the files --states and --truth name, which
// must lie in the log's folder) are copied into the caller's folder, so a case may change its copy.
#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "command_cache.hpp"
#include "run_command.hpp"

namespace jacobid::test {

// Runs `jacobid simulate --out <out> <args>` through the command cache; the result is simulate's own
// (exit code, output), and on success `out`, its truth JSON and the --states file, if asked for, exist.
inline CommandResult simulated_log(const std::string& out, const std::string& args) {
    namespace fs = std::filesystem;
    const fs::path target(out);
    std::vector<std::string> inputs, outputs{target.filename().string(), target.stem().string() + ".truth.json"};
    const std::string simulator = fixture_executable(JACOBID_EXECUTABLE);
    std::string command = simulator + " simulate --out {dir}/" + outputs.front();
    std::istringstream tokens(args);
    for (std::string token; tokens >> token;) {
        if (token == "--states" || token == "--truth") {
            std::string file;
            tokens >> file;
            if (fs::path(file).parent_path() != target.parent_path()) {
                ADD_FAILURE() << "simulated_log: " << token << " " << file << " must lie beside " << out;
                return {};
            }
            outputs.push_back(fs::path(file).filename().string());
            command += " " + token + " {dir}/" + outputs.back();
            continue;
        }
        if (token.find('/') != std::string::npos && fs::is_regular_file(token)) inputs.push_back(token);
        command += " " + token;
    }
    const CachedCommand c = cached_command(command, simulator, inputs);
    if (c.result.exit_code != 0) return c.result;
    for (const std::string& file : outputs) {
        if (fs::exists(c.dir / file)) fs::copy_file(c.dir / file, target.parent_path() / file, fs::copy_options::overwrite_existing);
    }
    return c.result;
}

}  // namespace jacobid::test
