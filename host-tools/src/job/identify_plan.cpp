// SPDX-License-Identifier: MIT
#include "job/identify_plan.hpp"

#include <utility>

#include "job/identify_inputs.hpp"

namespace jacobid::job {

MethodPlan plan_method(const std::vector<identify::LogColumns>& logs, const identify::SegmentSource& source, const robot::RobotDescription& robot,
                       const robot::RobotModel& model, const identify::PipelineSettings& settings, const identify::SolveOptions& solve,
                       std::optional<double> given_delay, const std::function<void(double)>& aligned) {
    MethodPlan plan;
    plan.method = settings.method;
    plan.segments = identify::plan_segments(logs, settings, source);
    const identify::LogColumns& reference = logs[plan.segments.reference];
    plan.delay = identify::resolve_torque_delay(model, reference, plan.segments.fixed, solve, given_delay);
    if (aligned) aligned(plan.delay.applied());
    {
        // An aligned copy of the reference's torques is not held through the identification.
        const identify::ShiftedTorques shifted = identify::shift_torques(reference, plan.delay.applied());
        plan.smoothed = identify::resolve_coulomb_smoothing(robot, model, shifted.log, plan.segments.fixed, solve.weighted);
    }
    // The Coulomb columns' velocity is chosen once too, on the reference with the model as smoothed: each piece
    // choosing from its own noise estimate made a log split at a gap differ from its halves.
    identify::PipelineSettings& fixed = plan.segments.fixed;
    if (fixed.coulomb_velocity_ratios.empty()) {
        fixed.coulomb_velocity_ratios = identify::coulomb_velocity_ratios(&plan.smoothed.get(model), reference, fixed, plan.segments.info);
    }
    return plan;
}

identify::SegmentedOutput factor_log(const MethodPlan& plan, const robot::RobotModel& nominal, const std::vector<identify::LogColumns>& pieces,
                                     int threads) {
    identify::PipelineSettings fixed = plan.segments.fixed;
    fixed.threads = threads;
    identify::OrderedMerge merged(fixed.plot_rows);
    for (const identify::LogColumns& piece : pieces) merged.add(identify::fold_segment(plan.smoothed.get(nominal), piece, fixed, plan.delay.applied()));
    return merged.result();
}

identify::IdentifiedLog solve_plan(MethodPlan plan, identify::SegmentedOutput merged, std::vector<identify::SegmentReport> pieces,
                                   const std::vector<std::string>& names, const robot::RobotModel& nominal, const identify::SolveOptions& solve) {
    std::vector<identify::SegmentReport> reports = piece_reports(std::move(pieces), names, merged, identify::to_string(plan.method));
    identify::IdentifiedLog fit =
        identify::solve_identification(std::move(merged.merged), std::move(plan.smoothed), std::move(plan.delay), nominal, solve);
    fit.result.segments = std::move(reports);
    return fit;
}

}  // namespace jacobid::job
