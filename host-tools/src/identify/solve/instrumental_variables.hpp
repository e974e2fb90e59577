// SPDX-License-Identifier: MIT
#pragma once
// IDIM-IV (Janot, Vandanjon, Gautier; docs/method.md, "Estimators"): the measured rows (W, y) of the
// pipeline, and instruments Z, the regressor of the identified model simulated in closed loop along the
// log's reference, through the same F_p and decimation. Z is correlated with W (same motion) but not with
// the measurement noise in W (it never sees the measured positions), so
//     X_iv = (Z' S W)^-1 Z' S y,     S = diag(s_j^2) the start's joint weights,
// is consistent where least squares is biased by noisy regressors. The instruments are rebuilt from each
// new estimate until X settles.
// Standard deviations: the IV sandwich s^2 (Z' S W)^-1 (Z' S Z) (W' S Z)^-1 with s^2 the weighted residual
// variance, rows taken as independent.
#include "identify/solve/estimator.hpp"
#include "identify/solve/reference_simulation.hpp"

namespace jacobid::identify {

// `start`: the WLS (or OLS) solution on the same log, whose joint weights IV keeps.
EstimatorRun identify_iv(const ReferenceSimulation& simulation, const EstimatorSettings& settings, const LsSolution& start, LsSolution& solution);

}  // namespace jacobid::identify
