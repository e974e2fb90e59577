// SPDX-License-Identifier: MIT
#include "diagnose/diagnose_log.hpp"

#include <optional>

#include "identify/friction/coulomb_smoothing.hpp"
#include "identify/pipeline/segmented_pipeline.hpp"
#include "sim/effect_terms.hpp"

namespace jacobid::diagnose {

Diagnosis diagnose_log(const robot::RobotDescription& robot, const robot::RobotModel& model, const identify::LogColumns& log,
                       const identify::LogColumns* validation, const DiagnoseSettings& settings,
                       const std::function<void(const std::string&)>& progress) {
    return diagnose_log(robot, model, std::vector<identify::LogColumns>{log}, validation, settings, progress);
}

Diagnosis diagnose_log(const robot::RobotDescription& robot, const robot::RobotModel& model, const std::vector<identify::LogColumns>& logs,
                       const identify::LogColumns* validation, const DiagnoseSettings& settings,
                       const std::function<void(const std::string&)>& progress) {
    // friction alpha: auto is chosen on the identification log (the longest of several, with the plan every
    // log gets), as identify does, before the search.
    const bool several = logs.size() > 1;
    std::optional<identify::SegmentPlan> plan;
    if (several) plan = identify::plan_segments(logs, settings.pipeline, {"--in", "log"});
    const identify::SmoothedModel smoothed = identify::resolve_coulomb_smoothing(
        robot, model, several ? logs[plan->reference] : logs.front(), several ? plan->fixed : settings.pipeline, false);
    robot::RobotDescription fitted = robot;
    std::vector<std::string> names;
    for (const auto& j : robot.joints) names.push_back(j.name);
    if (smoothed.choice) fitted.coulomb_alpha = smoothed.choice->alphas();
    sim::EffectContext context{model.model_name(), model.joint_count(), fitted.coulomb, robot::joint_coulomb_signs(fitted)};
    context.presliding_play = robot.presliding_play;  // presliding candidates filter flicker as identify's friction: presliding does
    // coulomb_load candidates, unless the model already has the FCLj columns they would repeat.
    if (robot.coulomb_load == robot::CoulombLoad::none) context.load = robot::gravity_load_reference(fitted);
    Diagnosis d = run_diagnosis(smoothed.get(model), context, logs, validation, settings, progress);
    d.joint_names = names;
    if (smoothed.choice) d.notes.push_back(identify::describe(*smoothed.choice, names));
    return d;
}

}  // namespace jacobid::diagnose
