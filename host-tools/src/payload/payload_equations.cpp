// SPDX-License-Identifier: MIT
#include "payload/payload_equations.hpp"

#include <fmt/core.h>

#include "identify/drive_gains/drive_gains.hpp"
#include "identify/friction/torque_delay.hpp"
#include "identify/validation/validation.hpp"
#include "payload/payload_inertia.hpp"
#include "payload/payload_rows.hpp"

namespace jacobid::payload {

PayloadEquations payload_equations(const ArmModel& arm, const identify::LogColumns& loaded, const identify::LogColumns* unloaded,
                                   const identify::IdentifySettings& s) {
    const robot::RobotModel& model = *arm.model;
    const int joints = model.joint_count();
    PayloadEquations e;
    // The torque delay: given, the arm's identification's, else estimated on the run the arm model describes.
    std::optional<double> given = s.torque_delay;
    if (!given && arm.torque_delay) {
        given = arm.torque_delay;
        e.delay_from_arm = true;
    }
    e.delay = identify::resolve_torque_delay(model, unloaded ? *unloaded : loaded, s.pipeline, s.solve, given);
    const identify::ShiftedTorques shifted_loaded = identify::shift_torques(loaded, e.delay.applied());

    const Eigen::MatrixXd& regrouping = arm.serial->base().regrouping;
    const std::vector<int> link = identify::last_link_columns(*arm.serial);
    Eigen::MatrixXd link_columns(regrouping.rows(), 10);
    for (int k = 0; k < 10; ++k) link_columns.col(k) = regrouping.col(link[static_cast<std::size_t>(k)]);

    std::optional<AlignedPair> pair;
    StoredRows reference;
    identify::PipelineOutput pipeline;
    e.source = loaded.source;
    if (unloaded) {
        e.source = fmt::format("{} and {}", loaded.source, unloaded->source);
        const identify::ShiftedTorques shifted_unloaded = identify::shift_torques(*unloaded, e.delay.applied());
        e.alignment = align_runs(shifted_loaded.log, shifted_unloaded.log);
        pair.emplace(aligned_pair(shifted_loaded.log, shifted_unloaded.log, *e.alignment));
        // The unloaded run decides the automatic choices; the loaded one is read with the same plan, so that the
        // rows fall on the same samples (as identify --drive-gains reads its pair).
        const identify::PipelineOutput first = identify::run_pipeline(model, pair->unloaded.log, s.pipeline, &reference);
        identify::PipelineSettings same = identify::validation_settings(s.pipeline, first.info);
        same.decimation = first.info.decimation;
        PayloadRows rows(joints, link_columns, arm.values, s.pipeline.residual_lags, &reference);
        pipeline = identify::run_pipeline(model, pair->loaded.log, same, &rows);
        e.factors = rows.factors();
    } else {
        PayloadRows rows(joints, link_columns, arm.values, s.pipeline.residual_lags);
        pipeline = identify::run_pipeline(model, shifted_loaded.log, s.pipeline, &rows);
        e.factors = rows.factors();
    }
    e.info = pipeline.info;

    e.names = standard_names();
    const auto c = static_cast<int>(arm.values.size());
    for (int k = 0; k < c; ++k) e.names.push_back(model.parameter_names()[static_cast<std::size_t>(k)]);
    for (int j = 0; j < joints; ++j) e.names.push_back(fmt::format("Y{}", j + 1));
    return e;
}

}  // namespace jacobid::payload
