// SPDX-License-Identifier: MIT
#include "io/increasing_rows.hpp"

#include <algorithm>
#include <functional>
#include <limits>

namespace jacobid::io {

std::vector<bool> longest_increasing_times(const std::vector<double>& t) {
    const std::size_t n = t.size();
    // longest[i]: the longest increasing run that starts at row i. From the end: latest_start[k] is the
    // latest start time of a run of k + 1 rows among the rows after i (decreasing in k); row i starts a run
    // one longer than the longest of those that start after t[i].
    std::vector<std::size_t> longest(n);
    std::vector<double> latest_start;
    for (std::size_t i = n; i-- > 0;) {
        const auto after = std::partition_point(latest_start.begin(), latest_start.end(), [&](double s) { return s > t[i]; });
        const auto k = static_cast<std::size_t>(after - latest_start.begin());
        longest[i] = k + 1;
        if (k == latest_start.size()) {
            latest_start.push_back(t[i]);
        } else {
            latest_start[k] = t[i];
        }
    }
    // The earliest row that starts a longest run, then each time the earliest later row that continues it.
    std::vector<bool> keep(n, false);
    std::size_t need = latest_start.size();
    double previous = -std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < n && need > 0; ++i) {
        if (longest[i] == need && t[i] > previous) {
            keep[i] = true;
            previous = t[i];
            --need;
        }
    }
    return keep;
}

}  // namespace jacobid::io
