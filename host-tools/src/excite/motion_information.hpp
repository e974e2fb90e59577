// SPDX-License-Identifier: MIT
#pragma once
// The information matrix of a sampled motion (excite's own trajectory at its control rate, or `--compare`'s
// trajectory or log): A = sum over the samples of W(q, qd, qdd)^T S^-1 W(q, qd, qdd), S = diag(sigma_j^2), the
// full-rate information the WLS estimate of identify keeps through its F_p and decimation (docs/excite.md,
// "Predicted std"). Long motions are summed over every k-th sample, each weighing k (at most `max_rows`
// samples: the regressor varies far slower than 1 / max_rows of a log).
#include <Eigen/Core>
#include <algorithm>
#include <cstddef>
#include <vector>

#include "robot/robot_model.hpp"

namespace jacobid::excite {

struct SampledMotion {
    std::vector<std::vector<double>> q, qd, qdd;  // per joint
    std::size_t first = 0, last = 0;              // the samples [first, last) count (last 0: all)
    std::size_t samples() const { return q.empty() ? 0 : q.front().size(); }
    // The samples [first, end) that count (first and last clamped to the samples).
    std::size_t end() const { return last == 0 ? samples() : std::min(last, samples()); }
    std::size_t begin() const { return std::min(first, end()); }
    std::size_t counted() const { return end() - begin(); }
};

Eigen::MatrixXd motion_information(const robot::RobotModel& model, const SampledMotion& motion, const Eigen::VectorXd& noise_std,
                                   std::size_t max_rows = 20000);

// The information identify's rows keep after its decimation filter F_p (a zero-phase Butterworth of `order` at
// `cutoff_hz`, as identify/pipeline/pipeline_fold.cpp applies it to both sides of the equations): sum over every sample of
// (F W)^T S^-1 (F W), F W each regressor column filtered along time at `sample_period` s. F projects white noise
// onto its passband, so this is the information of the filtered equations; a column with content above F_p (a
// Coulomb column's steps, accelerations) keeps less of its information than motion_information counts. One joint's
// regressor rows at every sample are held at a time (samples x columns doubles).
Eigen::MatrixXd filtered_motion_information(const robot::RobotModel& model, const SampledMotion& motion, const Eigen::VectorXd& noise_std,
                                            double sample_period, double cutoff_hz, int order = 4);

}  // namespace jacobid::excite
