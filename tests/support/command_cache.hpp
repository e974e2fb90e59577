// SPDX-License-Identifier: MIT
#pragma once
// A command run once and shared by the test processes that ask for the same one: gtest_discover_tests runs
// every test case in a process of its own, so a simulated log or a Monte Carlo study that several cases
// read was made again by each. The first process to ask runs the command in a folder of the build tree
// (tests/command-cache/<key>), holding a lock on it so that a case asking meanwhile (ctest -j) waits for
// the result instead of making it too; later ones read the folder.
//
// The key: the command with the calling process's scratch folder's name left out (each process has its
// own), the size and modification time of `executable` (a rebuilt jacobid makes new results), and the
// contents of the `inputs` files. A command that fails is not kept: the next asker runs it again.
#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "file_text.hpp"
#include "run_command.hpp"
#include "scratch_directory.hpp"

namespace jacobid::test {

struct CachedCommand {
    CommandResult result;
    std::filesystem::path dir;  // where the command's "{dir}" pointed: the files it wrote
};

namespace detail {

inline void replace_all(std::string& text, const std::string& from, const std::string& to) {
    for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size())) text.replace(at, from.size(), to);
}

inline std::string executable_stamp(const std::string& executable) {
    struct stat st {};
    if (::stat(executable.c_str(), &st) != 0) return "";
    return "\n" + std::to_string(st.st_size) + " " + std::to_string(st.st_mtim.tv_sec) + "." + std::to_string(st.st_mtim.tv_nsec);
}

}  // namespace detail

// The jacobid that makes a test's input logs (its simulations): JACOBID_FIXTURE_EXECUTABLE when set, else
// `under_test`. scripts/sanitize-test.sh sets it to the native build's jacobid: the sanitizer run then checks
// identify, monitor, payload ... under ASan on the logs the native run's simulator writes, which a simulation
// under ASan took 5-10 times longer to write (the 6-axis arm's 60 s log: 12.5 s). `jacobid simulate` itself
// still runs sanitized in the tests of simulate and of the pipelines that call it directly (serial and
// physical identification, diagnose's effect injection, excite).
inline std::string fixture_executable(const std::string& under_test) {
    const char* fixture = std::getenv("JACOBID_FIXTURE_EXECUTABLE");
    return fixture != nullptr && *fixture != '\0' ? std::string(fixture) : under_test;
}

// Runs `command` (a shell command; "{dir}" in it names the result's folder) once per key; see above.
inline CachedCommand cached_command(std::string command, const std::string& executable, const std::vector<std::string>& inputs = {}) {
    namespace fs = std::filesystem;
    std::string key_text = command;
    detail::replace_all(key_text, scratch_directory().string(), "<scratch>");
    key_text += detail::executable_stamp(executable);
    // A command that also runs the fixture executable (simulate && identify) is new when either is rebuilt.
    const std::string fixture = fixture_executable(executable);
    if (fixture != executable && command.find(fixture) != std::string::npos) key_text += detail::executable_stamp(fixture);
    for (const auto& input : inputs) key_text += "\n" + input.substr(input.find_last_of('/') + 1) + "\n" + file_text(input);
    char key[17];
    std::snprintf(key, sizeof key, "%016zx", std::hash<std::string>{}(key_text));

    const fs::path root = fs::path(JACOBID_BINARY_DIR) / "tests" / "command-cache";
    fs::create_directories(root);
    CachedCommand cached{{}, root / key};
    const int lock = ::open((root / (std::string(key) + ".lock")).c_str(), O_RDWR | O_CREAT, 0644);
    if (lock >= 0) ::flock(lock, LOCK_EX);  // released when closed
    if (fs::exists(cached.dir / "exit_code") && file_text(cached.dir / "command") == key_text) {
        cached.result.exit_code = std::stoi(file_text(cached.dir / "exit_code"));
        cached.result.out = file_text(cached.dir / "stdout");
        cached.result.err = file_text(cached.dir / "stderr");
    } else {
        fs::remove_all(cached.dir);
        fs::create_directories(cached.dir);
        detail::replace_all(command, "{dir}", cached.dir.string());
        cached.result = run_command(command);
        if (cached.result.exit_code == 0) {
            std::ofstream(cached.dir / "stdout", std::ios::binary) << cached.result.out;
            std::ofstream(cached.dir / "stderr", std::ios::binary) << cached.result.err;
            std::ofstream(cached.dir / "command", std::ios::binary) << key_text;
            std::ofstream(cached.dir / "exit_code") << cached.result.exit_code;  // written last: the result is complete
        }
    }
    if (lock >= 0) ::close(lock);
    return cached;
}

}  // namespace jacobid::test
