// SPDX-License-Identifier: MIT
#include "io/time_axis.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>

#include "core/errors.hpp"
#include "core/huge_pages.hpp"

namespace jacobid::io {

void require_plausible_sample_period(double median_step, const std::string& where) {
    if (median_step <= kMaxSamplePeriod) return;
    throw InputError(fmt::format("{}: the median time step is {:.6g} s, expected a sample period of at most {:g} s (is the time column in "
                                 "seconds? a log format's time.scale gives seconds per unit)",
                                 where, median_step, kMaxSamplePeriod));
}

TimeAxis check_uniform_time(const CsvTable& table, const std::string& column_name, double tolerance) {
    const std::vector<double>& t = table.column(column_name);
    if (t.size() < 2) {
        throw InputError(fmt::format("{}: column '{}' has {} sample(s), need at least 2 to know the sample period",
                                          table.source(), column_name, t.size()));
    }
    for (std::size_t i = 0; i + 1 < t.size(); ++i) {
        if (!(t[i + 1] > t[i])) {
            throw InputError(fmt::format("{}:{}: column '{}': time {} is not after the previous {} (time must increase)",
                                              table.source(), table.line_of_row(i + 1), column_name, t[i + 1], t[i]));
        }
    }
    // Each step is checked against the median step (robust: a gap or a burst of jitter cannot shift it),
    // so the message names the line of the first bad step; the sample period reported is then taken from
    // the end points, which averages the rounding of individual stamps.
    // One whole-log array (the steps, reordered by the selection); the check takes each step from t again.
    double median = 0.0;
    {
        std::vector<double> steps = huge_vector<double>(t.size() - 1);
        for (std::size_t i = 0; i + 1 < t.size(); ++i) steps[i] = t[i + 1] - t[i];
        std::nth_element(steps.begin(), steps.begin() + static_cast<std::ptrdiff_t>(steps.size() / 2), steps.end());
        median = steps[steps.size() / 2];
    }
    require_plausible_sample_period(median, fmt::format("{}: column '{}'", table.source(), column_name));
    for (std::size_t i = 0; i + 1 < t.size(); ++i) {
        const double step = t[i + 1] - t[i];
        if (std::abs(step - median) > tolerance * median) {
            throw InputError(fmt::format(
                "{}:{}: column '{}': time step {:.6g} s differs from the sample period {:.6g} s by more than {:.3g} % "
                "(non-uniform sampling or lost samples)",
                table.source(), table.line_of_row(i + 1), column_name, step, median, 100 * tolerance));
        }
    }
    const double ts = (t.back() - t.front()) / static_cast<double>(t.size() - 1);
    return {ts, t.front(), t.size()};
}

}  // namespace jacobid::io
