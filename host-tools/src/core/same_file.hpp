// SPDX-License-Identifier: MIT
#pragma once
// Whether two paths name the same file: compared as files (std::filesystem::equivalent: same device and
// inode, so a symlink or a hard link to a file is that file), not as strings. A path that does not exist yet
// (an output about to be written) is compared by its weakly canonical form, so "out/../a.csv" and "a.csv"
// are one file too. Used by every check that an output would overwrite an input, and that one input is not
// given twice (docs/reliability.md, issue 36).
#include <filesystem>
#include <system_error>

namespace jacobid {

inline bool same_file(const std::filesystem::path& a, const std::filesystem::path& b) {
    std::error_code error;
    if (std::filesystem::exists(a, error) && std::filesystem::exists(b, error)) {
        const bool equivalent = std::filesystem::equivalent(a, b, error);
        if (!error) return equivalent;
    }
    const auto canonical_a = std::filesystem::weakly_canonical(a, error);
    if (error) return false;
    const auto canonical_b = std::filesystem::weakly_canonical(b, error);
    if (error) return false;
    return canonical_a == canonical_b;
}

}  // namespace jacobid
