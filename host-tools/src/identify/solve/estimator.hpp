// SPDX-License-Identifier: MIT
#pragma once
// The estimators of `--estimator` (docs/method.md, "Estimators"): ordinary and weighted least squares on
// the pipeline's rows, and the two of Gautier, Janot and Vandanjon that start from the WLS estimate and
// iterate on closed-loop simulations of the identified model along the log's reference:
//  - iv:    IDIM-IV, the same measured rows, instruments from the simulated states (instrumental_variables.hpp);
//  - didim: DIDIM, the regressor of the simulated states against the measured torque (didim.hpp).
// Both stop when every parameter's relative change falls below `tolerance` or after
// `max_iterations`, and say which.
#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

#include "identify/solve/least_squares.hpp"

namespace jacobid::identify {

enum class Estimator { Ols, Wls, Iv, Didim };
const char* to_string(Estimator e);
// "ols" | "wls" | "iv" | "didim"; InputError naming --estimator otherwise.
Estimator parse_estimator(const std::string& name);
inline bool is_iterated(Estimator e) { return e == Estimator::Iv || e == Estimator::Didim; }

struct EstimatorSettings {
    Estimator estimator = Estimator::Wls;
    int max_iterations = 20;
    double tolerance = 1e-4;  // max over the identified parameters of |X_k+1 - X_k| / max(|X_k+1|, sigma)
};

// How an iterated estimator ended.
struct EstimatorRun {
    Estimator estimator = Estimator::Wls;
    int max_iterations = 0;
    double tolerance = 0.0;
    int iterations = 0;
    bool converged = false;
    std::vector<double> changes;  // relative change of X at each iteration
};

// One iteration: the new solution from the current one.
using EstimatorStep = std::function<LsSolution(const LsSolution& current)>;

// Iterates `step` from `start` (the WLS or OLS solution) until converged or max_iterations; `solution`
// receives the last iterate.
EstimatorRun iterate_estimator(const EstimatorSettings& settings, const LsSolution& start, const EstimatorStep& step, LsSolution& solution);

// The parameter vector to simulate: `solution.x`, InputError (naming the estimator) if a parameter is
// not identified (a simulation needs every parameter).
Eigen::VectorXd simulable_parameters(const LsSolution& solution, Estimator estimator);

}  // namespace jacobid::identify
