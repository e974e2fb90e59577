// SPDX-License-Identifier: MIT
#pragma once
// DIDIM (Gautier, Janot, Vandanjon; docs/method.md, "Estimators"): the identified model simulated in
// closed loop along the log's reference gives states free of measurement noise and of any
// differentiation; its regressor D(q_sim, qd_sim, qdd_sim) X is the simulated torque, so that the least
// squares of the measured torque on that regressor is one Gauss-Newton step of the output error
// ||tau - tau_sim(X)||. Torque and simulated columns go through the same F_p and decimation (and nothing
// else: the simulated states are exact), then the pipeline's (weighted) least squares and std.
#include "identify/solve/estimator.hpp"
#include "identify/solve/reference_simulation.hpp"

namespace jacobid::identify {

// `start`: the WLS (or OLS) solution; `solve` the options it was solved with. `factors` receives the last
// iteration's (simulated regressor, measured torque) factors.
EstimatorRun identify_didim(const ReferenceSimulation& simulation, const EstimatorSettings& settings, const LsSolution& start,
                            const SolveOptions& solve, LsSolution& solution, JointFactors& factors);

}  // namespace jacobid::identify
