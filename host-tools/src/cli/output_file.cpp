// SPDX-License-Identifier: MIT
#include "cli/output_file.hpp"

#include <fmt/core.h>

#include <cstdio>
#include <fstream>

#include "cli/command.hpp"

namespace jacobid::cli {

void write_output(const std::string& path, const std::string& text) {
    if (path == "-") {
        std::fwrite(text.data(), 1, text.size(), stdout);
        std::fflush(stdout);
        return;
    }
    std::ofstream out(path, std::ios::binary);
    if (!out) throw InputError(fmt::format("{}: cannot open for writing", path));
    out << text;
    if (!out) throw InputError(fmt::format("{}: write failed", path));
}

}  // namespace jacobid::cli
