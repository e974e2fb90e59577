// SPDX-License-Identifier: MIT
#include "identify/validation/segmented_validation.hpp"

#include <fmt/core.h>

#include <cmath>

#include "core/errors.hpp"
#include "identify/pipeline/segmented_pipeline.hpp"

namespace jacobid::identify {

ValidationResult pool_validations(const std::vector<ValidationResult>& parts, const std::string& source) {
    ValidationResult v;
    v.source = source;
    if (parts.empty()) return v;
    const std::size_t joints = parts.front().rms_error.size();
    std::vector<double> e2(joints, 0.0), raw2(joints, 0.0), y2(joints, 0.0);
    v.measured.resize(joints);
    v.predicted.resize(joints);
    v.raw_differentiator_cutoff = parts.front().raw_differentiator_cutoff;  // every part's settings are the same
    for (const ValidationResult& p : parts) {
        const auto n = static_cast<double>(p.samples), raw = static_cast<double>(p.raw_samples);
        v.samples += p.samples;
        v.raw_samples += p.raw_samples;
        for (std::size_t j = 0; j < joints; ++j) {
            e2[j] += n * p.rms_error[j] * p.rms_error[j];
            y2[j] += n * p.rms_torque[j] * p.rms_torque[j];
            raw2[j] += raw * p.raw_rms_error[j] * p.raw_rms_error[j];
            v.measured[j].insert(v.measured[j].end(), p.measured[j].begin(), p.measured[j].end());
            v.predicted[j].insert(v.predicted[j].end(), p.predicted[j].begin(), p.predicted[j].end());
        }
        v.t.insert(v.t.end(), p.t.begin(), p.t.end());
    }
    double e_all = 0.0, y_all = 0.0;
    for (std::size_t j = 0; j < joints; ++j) {
        v.rms_error.push_back(v.samples ? std::sqrt(e2[j] / static_cast<double>(v.samples)) : 0.0);
        v.rms_torque.push_back(v.samples ? std::sqrt(y2[j] / static_cast<double>(v.samples)) : 0.0);
        v.raw_rms_error.push_back(v.raw_samples ? std::sqrt(raw2[j] / static_cast<double>(v.raw_samples)) : 0.0);
        e_all += e2[j];
        y_all += y2[j];
    }
    v.relative_error = y_all > 0.0 ? std::sqrt(e_all / y_all) : 0.0;
    return v;
}

SegmentedValidation validate_segments(const robot::RobotModel& model, const std::vector<LogColumns>& segments, const PipelineSettings& settings,
                                      const Eigen::VectorXd& x, const std::string& source) {
    SegmentedValidation out;
    out.used.assign(segments.size(), false);
    out.why.assign(segments.size(), "");
    std::vector<ValidationResult> parts;
    for (std::size_t s = 0; s < segments.size(); ++s) {
        try {
            parts.push_back(validate_prediction(model, segments[s], settings, x));
            out.used[s] = true;
        } catch (const InputError& e) {
            out.why[s] = e.what();
        }
    }
    if (parts.empty()) {
        throw InputError(fmt::format("--validate {}: --on-gap split: none of the {} segments is usable: {}", source, segments.size(),
                                     joined_reasons(out.why)));
    }
    out.result = pool_validations(parts, source);
    return out;
}

}  // namespace jacobid::identify
