// SPDX-License-Identifier: MIT
#include "montecarlo/summary.hpp"

#include <cmath>
#include <limits>

namespace jacobid::montecarlo {

std::vector<ParameterSummary> summarize(const Study& study, const MethodRuns& runs, const Acceptance& acceptance) {
    constexpr double nan = std::numeric_limits<double>::quiet_NaN();
    std::vector<ParameterSummary> out;
    for (std::size_t p = 0; p < study.names.size(); ++p) {
        const auto i = static_cast<Eigen::Index>(p);
        ParameterSummary s;
        s.name = study.names[p];
        s.truth = study.truth[i];
        double sum = 0.0, sum_std = 0.0;
        int covered = 0;
        for (std::size_t k = 0; k < runs.x.size(); ++k) {
            const double x = runs.x[k][i], sd = runs.std_dev[k][i];
            if (!std::isfinite(x) || !std::isfinite(sd)) continue;
            ++s.runs;
            sum += x;
            sum_std += sd;
            if (std::abs(x - s.truth) <= 2.0 * sd) ++covered;
        }
        if (s.runs < 2) {
            s.mean = s.mean_error_percent = s.standard_error_percent = s.empirical_std = s.mean_reported_std = s.spread_ratio = s.coverage_2std = nan;
            out.push_back(s);
            continue;
        }
        const double n = s.runs;
        s.mean = sum / n;
        double squares = 0.0;
        for (std::size_t k = 0; k < runs.x.size(); ++k) {
            const double x = runs.x[k][i];
            if (std::isfinite(x) && std::isfinite(runs.std_dev[k][i])) squares += (x - s.mean) * (x - s.mean);
        }
        s.empirical_std = std::sqrt(squares / (n - 1.0));
        s.mean_reported_std = sum_std / n;
        s.spread_ratio = s.empirical_std / s.mean_reported_std;
        s.coverage_2std = covered / n;
        const double standard_error = s.empirical_std / std::sqrt(n);
        const double scale = s.truth != 0.0 ? 100.0 / std::abs(s.truth) : nan;
        s.mean_error_percent = (s.mean - s.truth) * scale;
        s.standard_error_percent = standard_error * scale;
        s.within_3se = std::abs(s.mean - s.truth) <= acceptance.standard_errors * standard_error;
        s.error_ok = s.within_3se || std::abs(s.mean_error_percent) <= acceptance.max_error_percent;
        s.spread_ok = s.spread_ratio >= acceptance.min_spread && s.spread_ratio <= acceptance.max_spread;
        s.coverage_ok = s.coverage_2std >= acceptance.min_coverage;
        out.push_back(s);
    }
    return out;
}

}  // namespace jacobid::montecarlo
