// SPDX-License-Identifier: MIT
#pragma once
// Writing command results: '-' is standard output, anything else a file (InputError if it cannot be
// written, naming the path).
#include <string>

namespace jacobid::cli {

void write_output(const std::string& path, const std::string& text);

}  // namespace jacobid::cli
