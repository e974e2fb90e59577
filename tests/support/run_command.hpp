// SPDX-License-Identifier: MIT
#pragma once
// Runs a shell command for CLI tests and captures its exit code, standard output and standard error.
#include <array>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

namespace jacobid::test {

struct CommandResult {
    int exit_code = -1;
    std::string out;
    std::string err;
};

inline CommandResult run_command(const std::string& command) {
    char err_path[] = "/tmp/jacobid-test-stderr-XXXXXX";
    const int fd = mkstemp(err_path);
    if (fd >= 0) close(fd);
    CommandResult r;
    FILE* pipe = popen((command + " 2>" + err_path).c_str(), "r");
    if (!pipe) return r;
    std::array<char, 65536> buffer{};
    std::size_t n;
    while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0) r.out.append(buffer.data(), n);
    const int status = pclose(pipe);
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    std::ifstream err(err_path);
    std::stringstream ss;
    ss << err.rdbuf();
    r.err = ss.str();
    std::remove(err_path);
    return r;
}

}  // namespace jacobid::test
