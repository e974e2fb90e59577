// SPDX-License-Identifier: MIT
#pragma once
// What the excite tests share: the command line, the planar 2R they design for, and their scratch files.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

#include "excite/information_criterion.hpp"

#include "scratch_directory.hpp"

namespace jacobid::test {

inline const std::string kJacobid = JACOBID_EXECUTABLE;
inline const std::string kTwoLink = std::string(JACOBID_SOURCE_DIR) + "/examples/robots/planar2r_mdh.yaml";

// A file `name` in the test's own scratch folder `folder` (created).
inline std::string excite_scratch(const std::string& folder, const std::string& name) {
    const std::filesystem::path dir = scratch_directory() / folder;
    std::filesystem::create_directories(dir);
    return (dir / name).string();
}

// The largest relative difference between a criterion's gradient in W and central differences of the criterion,
// over every `stride`-th entry of W (relative to |finite difference|, at least 1e-3).
inline double criterion_gradient_error(excite::Criterion criterion, const Eigen::MatrixXd& W, int joints, const excite::InformationModel& model,
                                       Eigen::Index stride) {
    Eigen::MatrixXd G;
    excite::evaluate_criterion(criterion, W, joints, model, &G);
    double worst = 0.0;
    for (Eigen::Index k = 0; k < W.size(); k += stride) {
        const double h = 1e-6 * std::max(1.0, std::abs(W.data()[k]));
        Eigen::MatrixXd plus = W, minus = W;
        plus.data()[k] += h, minus.data()[k] -= h;
        const double fd = (excite::evaluate_criterion(criterion, plus, joints, model, nullptr) - excite::evaluate_criterion(criterion, minus, joints, model, nullptr)) / (2 * h);
        worst = std::max(worst, std::abs(fd - G.data()[k]) / std::max(1e-3, std::abs(fd)));
    }
    return worst;
}

}  // namespace jacobid::test
