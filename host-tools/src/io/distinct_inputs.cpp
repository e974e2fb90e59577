// SPDX-License-Identifier: MIT
#include "io/distinct_inputs.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <fstream>
#include <system_error>

#include "core/errors.hpp"
#include "core/same_file.hpp"

namespace jacobid::io {
namespace {

// Whether two readable files of equal size hold the same bytes, read in blocks (logs may be gigabytes).
bool same_bytes(const std::string& a, const std::string& b) {
    std::ifstream fa(a, std::ios::binary), fb(b, std::ios::binary);
    if (!fa || !fb) return false;
    std::array<char, 1 << 16> ba{}, bb{};
    while (fa && fb) {
        fa.read(ba.data(), ba.size());
        fb.read(bb.data(), bb.size());
        if (fa.gcount() != fb.gcount() || !std::equal(ba.begin(), ba.begin() + fa.gcount(), bb.begin())) return false;
    }
    return fa.eof() && fb.eof();
}

}  // namespace

std::string same_log(const std::string& a, const std::string& b) {
    if (same_file(a, b)) return a == b ? "the same path" : fmt::format("{} and {} are one file (a link or another path to it)", a, b);
    std::error_code error_a, error_b;
    const auto size_a = std::filesystem::file_size(a, error_a), size_b = std::filesystem::file_size(b, error_b);
    if (!error_a && !error_b && size_a == size_b && same_bytes(a, b)) return fmt::format("{} is a byte-identical copy of {}", b, a);
    return {};
}

void require_distinct_inputs(const std::string& option, const std::vector<std::string>& paths) {
    for (std::size_t k = 0; k < paths.size(); ++k) {
        for (std::size_t l = k + 1; l < paths.size(); ++l) {
            const std::string why = same_log(paths[k], paths[l]);
            if (why.empty()) continue;
            throw InputError(fmt::format("{} {}: given twice ({} number {} and {}){}; give each log once (its equations would count twice)", option,
                                         paths[l], option, k + 1, l + 1, why == "the same path" ? std::string() : ", as " + why));
        }
    }
}

}  // namespace jacobid::io
