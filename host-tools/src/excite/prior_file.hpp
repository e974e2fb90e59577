// SPDX-License-Identifier: MIT
#pragma once
// `jacobid excite --prior identification.json`: an earlier identification (`jacobid identify --format json`)
// as the design's prior (docs/excite.md, "Prior and noise"):
//   - values: `parameters.<NAME>.value` for every base parameter of the model (a parameter the earlier run did
//     not identify keeps the description's value, and is listed in `fallbacks`);
//   - noise: per joint the std of the torque noise identify's WLS estimate sees at the log's full rate,
//     sigma_j sqrt(d f_j) from `joint_sigma` (the residual std at the decimated rows), `settings.decimation` d and
//     `joint_long_run_factors` f_j (1 when absent): identify's joint-hac variance sigma_j^2 f_j per decimated row
//     is that of d full-rate rows of noise sigma_j^2 d f_j, so the same noise predicts its std.
// InputError naming the file and the key for anything else.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "robot/robot_model.hpp"

namespace jacobid::excite {

struct PriorFile {
    Eigen::VectorXd values;     // per base parameter of the model
    Eigen::VectorXd noise_std;  // per joint, N.m (full-rate equivalent)
    std::vector<std::string> fallbacks;  // parameters not identified there: the description's values kept
};

// `description_values`: the model's parameters from the robot description (the fallback).
PriorFile read_prior_file(const std::string& path, const robot::RobotModel& model, const Eigen::VectorXd& description_values);

}  // namespace jacobid::excite
