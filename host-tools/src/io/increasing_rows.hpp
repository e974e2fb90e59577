// SPDX-License-Identifier: MIT
#pragma once
// Which rows of a log --skip-bad-rows keeps so that time increases. Comparing each row with the last one
// kept let one corrupt row poison the rest: a time of 1e154 near the start made every real row "not after"
// it, so all of them were skipped and the few corrupt rows were the log ("the median time step is
// 2.68e+154 s"). Keeping the longest strictly increasing run of times instead skips the fewest rows, and
// the corrupt ones are what does not fit, wherever they are.
#include <cstddef>
#include <vector>

namespace jacobid::io {

// Of the rows with times t, the most rows whose times strictly increase (a longest strictly increasing
// subsequence), the earliest rows among equally long choices (of two rows with one time, the first is kept).
// O(n log n). keep[i] says whether row i is kept.
std::vector<bool> longest_increasing_times(const std::vector<double>& t);

}  // namespace jacobid::io
