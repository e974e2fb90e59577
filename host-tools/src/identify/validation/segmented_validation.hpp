// SPDX-License-Identifier: MIT
#pragma once
// Cross-validation on a validation log split at its gaps (--on-gap split): validate_prediction on every
// segment with the identification's settings, the figures pooled over the segments as if their compared
// samples were one record (RMS errors weighted by sample counts, the relative error from the pooled sums
// of squares). A segment too short for the identification's windows is not used, with its reason.
#include <string>
#include <vector>

#include "identify/validation/validation.hpp"

namespace jacobid::identify {

struct SegmentedValidation {
    ValidationResult result;       // pooled; source = `source`
    std::vector<bool> used;        // per segment
    std::vector<std::string> why;  // per segment: the reason when not used
};

// InputError when no segment is usable, naming each one's reason.
SegmentedValidation validate_segments(const robot::RobotModel& model, const std::vector<LogColumns>& segments, const PipelineSettings& settings,
                                      const Eigen::VectorXd& x, const std::string& source);

// The pooled figures of `parts` (validate_prediction results of disjoint records of one robot).
ValidationResult pool_validations(const std::vector<ValidationResult>& parts, const std::string& source);

}  // namespace jacobid::identify
