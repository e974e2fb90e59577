// SPDX-License-Identifier: MIT
#include "identify/solve/didim.hpp"

#include <utility>

namespace jacobid::identify {

EstimatorRun identify_didim(const ReferenceSimulation& simulation, const EstimatorSettings& settings, const LsSolution& start,
                            const SolveOptions& solve, LsSolution& solution, JointFactors& factors) {
    return iterate_estimator(settings, start, [&](const LsSolution& current) {
        PipelineOutput out = fold_states(simulation.model, simulation.log, simulation.pipeline, simulation.info,
                                         simulation.states(simulable_parameters(current, Estimator::Didim)));
        factors = std::move(out.factors);
        return solve_least_squares(factors, current.names, solve);
    }, solution);
}

}  // namespace jacobid::identify
