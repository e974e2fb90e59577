// SPDX-License-Identifier: MIT
#pragma once
// Presentation of identification results: the paper's Table II layout (X^, 2 sigma, %sigma_r per
// parameter, methods side by side, optionally next to the truth of a simulation), JSON, and a Markdown
// report with PNG plots (filtered torque measured vs model, validation).
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "identify/friction/coulomb_smoothing.hpp"
#include "identify/solve/estimator.hpp"
#include "identify/solve/least_squares.hpp"
#include "identify/physical/physical_least_squares.hpp"
#include "identify/pipeline/pipeline.hpp"
#include "identify/physical/plausibility.hpp"
#include "identify/validation/static_validation.hpp"
#include "identify/friction/torque_delay.hpp"
#include "identify/validation/validation.hpp"

namespace jacobid::identify {

// One segment of a log split at its gaps (--on-gap split), as the reports list it.
// One piece of the identification's data: a segment of a log cut at its gaps (--on-gap split) and/or one
// of several logs (--in a --in b).
struct SegmentReport {
    std::size_t first_line = 0, last_line = 0;  // 0: the whole log
    double duration = 0.0;  // s
    std::size_t samples = 0;
    bool used = false;
    std::string why;       // the reason when not used
    std::size_t rows = 0;  // equations per joint it gave (0 when not used or not counted)
    std::string log;       // the log's path when several logs are identified together, else empty
};

struct MethodResult {
    PipelineInfo info;
    LsSolution solution;
    std::optional<EssentialResult> essential;
    std::optional<ValidationResult> validation;
    std::optional<StaticValidationResult> static_validation;  // --validate with a log that holds a pose
    std::vector<PlausibilityViolation> violations;
    TorqueDelayResult torque_delay;
    std::optional<CoulombSmoothingChoice> coulomb_smoothing;  // friction alpha: auto
    std::optional<PhysicalReport> physical;                   // --physical / --semi-physical
    std::optional<PreslidingDisplacementChoice> presliding_displacement;  // friction presliding_displacement: auto
    PlotRows plot;
    // Which segments of a log split at its gaps (--on-gap split) the method used; empty otherwise.
    std::vector<SegmentReport> segments, validation_segments;
    // --estimator iv | didim: how the iteration ended (absent: the least squares of `solution`).
    std::optional<EstimatorRun> estimator;
};

struct ReportContext {
    std::string log_source;
    std::string model_name;
    std::vector<std::string> joint_names;
    std::map<std::string, double> truth;  // empty: unknown
    std::vector<std::string> warnings;
};

// Human-readable warnings about what cannot be identified (zero columns, null combinations, joints that
// do not move).
std::vector<std::string> identifiability_warnings(const MethodResult& result, const std::vector<std::string>& joint_names);

std::string format_table(const std::vector<MethodResult>& results, const ReportContext& context);
nlohmann::json to_json(const MethodResult& result, const ReportContext& context);
// Writes DIR/report.md and DIR/torque_<method>_<joint>.png (and validation plots). Throws InputError if
// DIR cannot be created.
void write_report(const std::string& directory, const std::vector<MethodResult>& results, const ReportContext& context);

}  // namespace jacobid::identify
