// SPDX-License-Identifier: MIT
#include "io/distinct_inputs.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <cstdint>
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

void require_distinct_inputs(const std::string& option, const std::vector<std::string>& paths) {
    std::vector<std::uintmax_t> sizes(paths.size(), static_cast<std::uintmax_t>(-1));
    for (std::size_t k = 0; k < paths.size(); ++k) {
        std::error_code error;
        const auto size = std::filesystem::file_size(paths[k], error);
        if (!error) sizes[k] = size;
    }
    for (std::size_t k = 0; k < paths.size(); ++k) {
        for (std::size_t l = k + 1; l < paths.size(); ++l) {
            std::string why;
            if (same_file(paths[k], paths[l])) {
                if (paths[k] != paths[l]) why = fmt::format(", as {} and {} are one file (a link or another path to it)", paths[k], paths[l]);
            } else if (sizes[k] == sizes[l] && sizes[k] != static_cast<std::uintmax_t>(-1) && same_bytes(paths[k], paths[l])) {
                why = fmt::format(", as {} is a byte-identical copy of {}", paths[l], paths[k]);
            } else {
                continue;
            }
            throw InputError(fmt::format("{} {}: given twice ({} number {} and {}){}; give each log once (its equations would count twice)", option,
                                         paths[l], option, k + 1, l + 1, why));
        }
    }
}

}  // namespace jacobid::io
