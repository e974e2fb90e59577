// SPDX-License-Identifier: MIT
#include "identify/validation/validate_log.hpp"

#include "identify/validation/static_validation.hpp"
#include "identify/friction/torque_delay.hpp"
#include "identify/validation/validation.hpp"

namespace jacobid::identify {

void validate_log(const robot::RobotModel& model, const LogColumns& log, const PipelineSettings& settings, double min_joint_motion,
                  MethodResult& r) {
    if (is_static(log, min_joint_motion)) {
        r.static_validation = validate_static(model, log, r.solution.x);
        return;
    }
    // The same hardware, the same offset between its channels.
    const ShiftedTorques aligned = shift_torques(log, r.torque_delay.applied());
    r.validation = validate_prediction(model, aligned.log, validation_settings(settings, r.info), r.solution.x);
}

}  // namespace jacobid::identify
