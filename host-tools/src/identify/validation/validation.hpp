// SPDX-License-Identifier: MIT
#pragma once
// Cross-validation: the torques of a second trajectory predicted with identified parameters. The main
// figure compares them as the identification does, after the same decimation filter F_p on both sides
// (measured Y vs W X^ on the new trajectory): the full-rate comparison is dominated by the encoder
// quantization amplified in the acceleration estimates (e.g. 2^16 counts/rev at 1 kHz: ~0.2 N.m on
// joint 1), which F_p removes exactly as in the identification. The raw full-rate RMS is reported too.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "identify/pipeline/pipeline.hpp"
#include "robot/robot_model.hpp"

namespace jacobid::identify {

struct ValidationResult {
    std::string source;
    std::size_t samples = 0;            // compared samples per joint
    std::size_t raw_samples = 0;        // full-rate samples of the raw comparison
    std::vector<double> rms_error;      // per joint, N.m, filtered (F_p) measured - predicted
    std::vector<double> raw_rms_error;  // per joint, N.m, full-rate raw measured - predicted
    double raw_differentiator_cutoff = 0.0;  // Hz: the differentiators of the raw comparison
    std::vector<double> rms_torque;     // per joint, N.m
    double relative_error = 0.0;        // ||Y - W X|| / ||Y|| over all joints (filtered)
    std::vector<double> t;              // a few thousand samples for plots
    std::vector<std::vector<double>> measured, predicted;
};

// The settings for a second log (a validation log, or a log compared with an identification, as in
// `jacobid diagnose`): `identification` with the identification's resolved choices from `info` (bandwidth,
// Jacobi windows in seconds, differentiator and F_p cutoffs in Hz), so that both logs go through the same
// differentiators and the same F_p even when their own motion bandwidths differ. Progress messages off.
PipelineSettings validation_settings(const PipelineSettings& identification, const PipelineInfo& info);

// Parameters not identified (NaN in x) count as 0. `settings` should carry the windows used for the
// identification (same cutoffs in Hz): validation_settings().
ValidationResult validate_prediction(const robot::RobotModel& model, const LogColumns& log, const PipelineSettings& settings,
                                     const Eigen::VectorXd& x);

}  // namespace jacobid::identify
