#include "io/time_axis.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>

#include "cli/command.hpp"

namespace jacobid::io {

TimeAxis check_uniform_time(const CsvTable& table, const std::string& column_name, double tolerance) {
    const std::vector<double>& t = table.column(column_name);
    if (t.size() < 2) {
        throw cli::InputError(fmt::format("{}: column '{}' has {} sample(s), need at least 2 to know the sample period",
                                          table.source(), column_name, t.size()));
    }
    for (std::size_t i = 0; i + 1 < t.size(); ++i) {
        if (!(t[i + 1] > t[i])) {
            throw cli::InputError(fmt::format("{}:{}: column '{}': time {} is not after the previous {} (time must increase)",
                                              table.source(), table.line_of_row(i + 1), column_name, t[i + 1], t[i]));
        }
    }
    // The sample period from the end points (robust to rounding of individual stamps); each step is then
    // checked against it, so a gap or a jitter beyond the tolerance is reported at its line.
    const double ts = (t.back() - t.front()) / static_cast<double>(t.size() - 1);
    for (std::size_t i = 0; i + 1 < t.size(); ++i) {
        const double step = t[i + 1] - t[i];
        if (std::abs(step - ts) > tolerance * ts) {
            throw cli::InputError(fmt::format(
                "{}:{}: column '{}': time step {:.6g} s differs from the sample period {:.6g} s by more than {:.3g} % "
                "(non-uniform sampling or lost samples)",
                table.source(), table.line_of_row(i + 1), column_name, step, ts, 100 * tolerance));
        }
    }
    return {ts, t.front(), t.size()};
}

}  // namespace jacobid::io
