// SPDX-License-Identifier: MIT
#pragma once
// The payload's equations (payload_estimate.hpp): the torque delay (given, the arm's identification's, or
// estimated on the run the arm model describes), the time alignment of the unloaded run (time_alignment.hpp), and
// identify's pipeline on the run(s) folded by PayloadRows (payload_rows.hpp) into per-joint factors over
// [payload (10) | arm (c) | efforts (joints) | right-hand side].
#include <optional>
#include <string>
#include <vector>

#include "identify/identify_run.hpp"
#include "payload/arm_file.hpp"
#include "payload/time_alignment.hpp"

namespace jacobid::payload {

struct PayloadEquations {
    identify::JointFactors factors;
    std::vector<std::string> names;  // XX .. M, the arm's base parameters, Y1 .. Yn
    identify::PipelineInfo info;
    identify::TorqueDelayResult delay;
    bool delay_from_arm = false;  // the delay the arm's identification applied (its JSON), not --torque-delay's
    std::optional<Alignment> alignment;
    std::string source;  // the log(s) the rows come from, for messages
};

PayloadEquations payload_equations(const ArmModel& arm, const identify::LogColumns& loaded, const identify::LogColumns* unloaded,
                                   const identify::IdentifySettings& settings);

}  // namespace jacobid::payload
