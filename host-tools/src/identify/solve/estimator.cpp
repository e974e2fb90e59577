// SPDX-License-Identifier: MIT
#include "identify/solve/estimator.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>

#include "core/errors.hpp"

namespace jacobid::identify {

const char* to_string(Estimator e) {
    switch (e) {
        case Estimator::Ols: return "ols";
        case Estimator::Wls: return "wls";
        case Estimator::Iv: return "iv";
        case Estimator::Didim: return "didim";
    }
    return "?";
}

Estimator parse_estimator(const std::string& name) {
    for (const Estimator e : {Estimator::Ols, Estimator::Wls, Estimator::Iv, Estimator::Didim}) {
        if (name == to_string(e)) return e;
    }
    throw InputError(fmt::format("--estimator '{}': expected ols, wls, iv or didim", name));
}

Eigen::VectorXd simulable_parameters(const LsSolution& solution, Estimator estimator) {
    for (Eigen::Index c = 0; c < solution.x.size(); ++c) {
        if (!std::isfinite(solution.x[c])) {
            throw InputError(fmt::format("--estimator {}: parameter {} is not identified, and the model cannot be simulated without it",
                                         to_string(estimator), solution.names[static_cast<std::size_t>(c)]));
        }
    }
    return solution.x;
}

EstimatorRun iterate_estimator(const EstimatorSettings& settings, const LsSolution& start, const EstimatorStep& step, LsSolution& solution) {
    EstimatorRun run;
    run.estimator = settings.estimator;
    run.max_iterations = settings.max_iterations;
    run.tolerance = settings.tolerance;
    solution = start;
    for (int k = 0; k < settings.max_iterations; ++k) {
        LsSolution next = step(solution);
        // Each parameter's change relative to its own size (a vector norm would be ZZ1R's alone and stop
        // while a small friction coefficient still drifts), or to its std when it is smaller than that (a
        // parameter near 0 has no relative change to settle).
        double relative = 0.0;
        for (Eigen::Index c = 0; c < next.x.size(); ++c) {
            if (!std::isfinite(next.x[c]) || !std::isfinite(solution.x[c])) continue;
            const double scale = std::max(std::abs(next.x[c]), std::isfinite(next.std_dev[c]) ? next.std_dev[c] : 0.0);
            if (scale > 0.0) relative = std::max(relative, std::abs(next.x[c] - solution.x[c]) / scale);
        }
        solution = std::move(next);
        run.iterations = k + 1;
        run.changes.push_back(relative);
        if (relative < settings.tolerance) {
            run.converged = true;
            break;
        }
    }
    return run;
}

}  // namespace jacobid::identify
