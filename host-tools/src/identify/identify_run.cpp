// SPDX-License-Identifier: MIT
#include "identify/identify_run.hpp"

#include <utility>

#include "identify/solve/didim.hpp"
#include "identify/solve/instrumental_variables.hpp"
#include "identify/physical/plausibility.hpp"
#include "identify/solve/reference_simulation.hpp"

namespace jacobid::identify {

TorqueDelayResult resolve_torque_delay(const robot::RobotModel& model, const LogColumns& log, const PipelineSettings& pipeline,
                                       const SolveOptions& solve, std::optional<double> given) {
    TorqueDelayResult r;
    if (given) {
        r.given = true;
        r.estimate.delay = *given;
        r.estimate.compensated = *given != 0.0;
        return r;
    }
    r.estimate = estimate_torque_delay(model, log, pipeline, solve);
    return r;
}

IdentifiedLog solve_identification(PipelineOutput out, SmoothedModel smoothed, TorqueDelayResult delay, const robot::RobotModel& nominal,
                                   const SolveOptions& solve) {
    IdentifiedLog fit;
    const robot::RobotModel& fitted = smoothed.get(nominal);
    MethodResult& r = fit.result;
    r.torque_delay = std::move(delay);
    r.coulomb_smoothing = smoothed.choice;
    r.presliding_displacement = smoothed.presliding;
    r.info = std::move(out.info);
    r.plot = std::move(out.plot);
    r.solution = solve_least_squares(out.factors, fitted.parameter_names(), solve);
    r.violations = plausibility_violations(sign_constraints(fitted), r.solution);
    fit.factors = std::move(out.factors);
    fit.smoothed = std::move(smoothed);
    return fit;
}

void refine_estimate(const robot::RobotDescription& description, const robot::RobotModel& nominal, const LogColumns& aligned,
                     const IdentifySettings& settings, IdentifiedLog& fit) {
    const Estimator estimator = settings.estimator.estimator;
    if (!is_iterated(estimator)) return;
    require_reference_simulation(aligned, description, to_string(estimator));
    const robot::RobotModel& fitted = fit.smoothed.get(nominal);
    const ReferenceSimulation simulation{description, nominal, fitted, aligned, settings.pipeline, fit.result.info};
    MethodResult& r = fit.result;
    const LsSolution start = r.solution;
    r.estimator = estimator == Estimator::Iv ? identify_iv(simulation, settings.estimator, start, r.solution)
                                             : identify_didim(simulation, settings.estimator, start, settings.solve, r.solution, fit.factors);
    r.violations = plausibility_violations(sign_constraints(fitted), r.solution);
}

IdentifiedLog identify_log(const robot::RobotDescription& description, const robot::RobotModel& nominal, const LogColumns& log,
                           const IdentifySettings& settings) {
    // The delay is estimated with the description's alpha, then each joint's alpha (friction alpha: auto) is
    // chosen on the aligned log.
    // A log an iterated estimator cannot simulate along fails before any work.
    if (is_iterated(settings.estimator.estimator)) require_reference_simulation(log, description, to_string(settings.estimator.estimator));
    TorqueDelayResult delay = resolve_torque_delay(nominal, log, settings.pipeline, settings.solve, settings.torque_delay);
    const ShiftedTorques aligned = shift_torques(log, delay.applied());
    SmoothedModel smoothed = resolve_coulomb_smoothing(description, nominal, aligned.log, settings.pipeline, settings.solve.weighted);
    PipelineOutput out = run_pipeline(smoothed.get(nominal), aligned.log, settings.pipeline);
    IdentifiedLog fit = solve_identification(std::move(out), std::move(smoothed), std::move(delay), nominal, settings.solve);
    refine_estimate(description, nominal, aligned.log, settings, fit);
    return fit;
}

}  // namespace jacobid::identify
