// SPDX-License-Identifier: MIT
#include "io/time_axis.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>

#include "core/errors.hpp"
#include "core/huge_pages.hpp"

namespace jacobid::io {

namespace {

// 0.001 -> "1 ms", for the messages about sample periods.
std::string period_text(double seconds) {
    seconds *= 1.0 + 1e-9;  // a period of 1e-12 / 1e-9 is 1 ms, not 999.99... us
    if (seconds >= 1.0) return fmt::format("{:.4g} s", seconds);
    if (seconds >= 1e-3) return fmt::format("{:.4g} ms", 1e3 * seconds);
    if (seconds >= 1e-6) return fmt::format("{:.4g} us", 1e6 * seconds);
    return fmt::format("{:.4g} s", seconds);
}

}  // namespace

void require_plausible_sample_period(double median_step, const std::string& where, double scale, const std::string& format) {
    if (median_step >= kMinSamplePeriod && median_step <= kMaxSamplePeriod) return;
    // The units the column's raw numbers could be in that give a plausible period, each with the scale that reads it.
    const double raw = median_step / scale;
    struct Unit {
        const char* name;
        double seconds;
    };
    std::string likely;
    for (const Unit u : {Unit{"s", 1.0}, Unit{"ms", 1e-3}, Unit{"us", 1e-6}, Unit{"ns", 1e-9}}) {
        const double step = raw * u.seconds;
        if (!(step >= kMinSamplePeriod && step <= kMaxSamplePeriod) || u.seconds == scale) continue;
        likely += fmt::format("{}in {} ({} per sample: time.scale {:g})", likely.empty() ? "is the time column " : " or ", u.name, period_text(step),
                              u.seconds);
    }
    likely = likely.empty() ? std::string("is the time column in seconds?") : likely + "?";
    const std::string how = format.empty() ? std::string("a --log-format file's time: {column: ..., scale: ...} reads other units")
                                           : fmt::format("{} reads it with time.scale {:g} s per unit", format, scale);
    throw InputError(fmt::format("{}: the median time step is {:.6g} s, outside the plausible sample periods {} .. {} per sample (100 kHz .. 10 Hz): "
                                 "{} ({})",
                                 where, median_step, period_text(kMinSamplePeriod), period_text(kMaxSamplePeriod), likely, how));
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
