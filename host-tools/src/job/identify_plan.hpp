// SPDX-License-Identifier: MIT
#pragma once
// Several logs identified together as a map-reduce (docs/fleet.md): a method's set-up resolved once (plan), each
// log reduced on its own to its factors (factor), the factors merged in log order and solved (merge, solve).
// `jacobid identify --in a --in b ...` runs exactly these pieces (job/identify_job.cpp), and so do the Python
// module's jacobid.plan / factor / merge (python/src/fleet_bindings.cpp), on one machine or on a fleet's workers.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "identify/friction/coulomb_smoothing.hpp"
#include "identify/identify_run.hpp"
#include "identify/pipeline/segmented_pipeline.hpp"
#include "identify/friction/torque_delay.hpp"
#include "robot/robot_description.hpp"
#include "robot/robot_model.hpp"

namespace jacobid::job {

// One method's set-up for every log identified together, resolved on the longest of them.
struct MethodPlan {
    identify::Method method = identify::Method::Jacobi;
    identify::SegmentPlan segments;     // the reference log's plan; segments.fixed (with the Coulomb columns' velocity) imposed on every log
    identify::TorqueDelayResult delay;  // the torque delay every log is aligned by
    identify::SmoothedModel smoothed;   // the model every log is folded with: smoothed.get(nominal)
};

// The plan of `settings.method` on the longest of `logs`: its pipeline plan, the torque delay (given or estimated),
// the Coulomb smoothing and the Coulomb columns' velocity. `aligned(delay)`, if given, runs between the delay and
// the smoothing (a log read piece by piece aligns its first piece in place there). InputError as plan_segments.
MethodPlan plan_method(const std::vector<identify::LogColumns>& logs, const identify::SegmentSource& source, const robot::RobotDescription& robot,
                       const robot::RobotModel& model, const identify::PipelineSettings& settings, const identify::SolveOptions& solve,
                       std::optional<double> given_delay, const std::function<void(double)>& aligned = {});

// One log's factors with `plan`: each of its pieces (one, or its segments with --on-gap split) folded on its own
// (identify::fold_segment) and merged in order (identify::OrderedMerge); `threads` inside each piece's pipeline. A piece that gives no
// equations is kept with its reason, as identify keeps it.
identify::SegmentedOutput factor_log(const MethodPlan& plan, const robot::RobotModel& nominal, const std::vector<identify::LogColumns>& pieces,
                                     int threads);

// The merged factors of every log (identify::OrderedMerge in log order, identify::finish_segments) solved:
// the pieces' report lines (`pieces` and `names` as read_inputs made them; a piece not used also on stderr) and
// the least squares with the plan's delay and smoothing.
identify::IdentifiedLog solve_plan(MethodPlan plan, identify::SegmentedOutput merged, std::vector<identify::SegmentReport> pieces,
                                   const std::vector<std::string>& names, const robot::RobotModel& nominal, const identify::SolveOptions& solve);

}  // namespace jacobid::job
