// SPDX-License-Identifier: MIT
#pragma once
// The one check that the logs a command reads together (identify --in a --in b, diagnose --in ...) are
// different logs: one log twice counts its equations twice, so every standard deviation comes out too
// small by sqrt(2) and the result looks better than the data is. Twice means the same file under another
// path (a symlink, a hard link, "./a.csv": core/same_file.hpp) or a byte-identical copy under another name.
#include <string>
#include <vector>

namespace jacobid::io {

// Why `b` is the log `a` ("a.csv and b.csv are one file (a link or another path to it)", "b.csv is a
// byte-identical copy of a.csv", "the same path"), or "" when they are different logs. Files that cannot be
// read are different here: the reader names them.
std::string same_log(const std::string& a, const std::string& b);

// InputError "--in b.csv: given twice (--in number 1 and 2), as b.csv is a byte-identical copy of a.csv; ..."
// for the first such pair.
void require_distinct_inputs(const std::string& option, const std::vector<std::string>& paths);

}  // namespace jacobid::io
