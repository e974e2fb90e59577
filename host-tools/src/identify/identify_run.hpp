// SPDX-License-Identifier: MIT
#pragma once
// One method's identification of one log, as `jacobid identify` does it: the torque delay (estimated or
// given), the Coulomb smoothing of `friction: {alpha: auto}` chosen on the aligned log, the pipeline, the
// least squares and the plausibility checks. Shared by `jacobid identify` and `jacobid montecarlo`, so that
// a Monte Carlo study checks exactly what users run.
#include <optional>

#include "identify/friction/coulomb_smoothing.hpp"
#include "identify/solve/estimator.hpp"
#include "identify/solve/least_squares.hpp"
#include "identify/pipeline/pipeline.hpp"
#include "identify/report/report.hpp"
#include "identify/friction/torque_delay.hpp"
#include "robot/robot_description.hpp"
#include "robot/robot_model.hpp"

namespace jacobid::identify {

struct IdentifySettings {
    PipelineSettings pipeline;           // pipeline.method: the method
    SolveOptions solve;
    std::optional<double> torque_delay;  // s, given (0: off); nullopt: estimated (--torque-delay auto)
    // ols | wls: the least squares of `solve`; iv | didim: iterated from it (estimator.hpp).
    EstimatorSettings estimator;
};

// What the rest of identify (essential parameters, validation, reports) needs beside the result.
struct IdentifiedLog {
    MethodResult result;  // torque_delay, coulomb_smoothing, info, plot, solution, violations
    JointFactors factors;
    SmoothedModel smoothed;  // the model fitted: smoothed.get(nominal)
};

// The given delay, or the least-squares estimate on `log` (torque_delay.hpp).
TorqueDelayResult resolve_torque_delay(const robot::RobotModel& model, const LogColumns& log, const PipelineSettings& pipeline,
                                       const SolveOptions& solve, std::optional<double> given);

// The least squares on a pipeline's output and the checks that follow from it alone.
IdentifiedLog solve_identification(PipelineOutput out, SmoothedModel smoothed, TorqueDelayResult delay, const robot::RobotModel& nominal,
                                   const SolveOptions& solve);

// IDIM-IV or DIDIM (settings.estimator) from fit's least-squares solution on `aligned` (the log with
// fit's torque delay applied): fit.result.solution and .estimator become the estimator's, and DIDIM's
// factors replace fit.factors.
void refine_estimate(const robot::RobotDescription& description, const robot::RobotModel& nominal, const LogColumns& aligned,
                     const IdentifySettings& settings, IdentifiedLog& fit);

// The whole flow on one log (one segment); settings.estimator iv or didim refine it (refine_estimate). InputError as run_pipeline (log too short ...).
IdentifiedLog identify_log(const robot::RobotDescription& description, const robot::RobotModel& nominal, const LogColumns& log,
                           const IdentifySettings& settings);

}  // namespace jacobid::identify
