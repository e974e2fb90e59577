// SPDX-License-Identifier: MIT
#pragma once
// What `jacobid excite` predicts before the robot moves (docs/excite.md, "Predicted std"): the prior and
// noise the information criteria weigh (--prior, --torque-noise), the motion of `--compare FILE` (a
// trajectory table or a recorded log), and the predicted std of every base parameter as text and JSON.
#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "options/log_format_options.hpp"
#include "excite/information_criterion.hpp"
#include "excite/motion_information.hpp"
#include "excite/payload_target.hpp"
#include "robot/robot_description.hpp"
#include "robot/robot_model.hpp"

namespace jacobid::cli {

struct ExcitePrior {
    Eigen::VectorXd values;     // per base parameter
    Eigen::VectorXd noise_std;  // per joint, N.m
    Eigen::VectorXd scales;     // per base parameter (excite/parameter_scales.hpp)
    std::string values_source;  // "the robot description" or the --prior file
    std::string noise_source;   // "--torque-noise", the --prior file, or "unit (1 N.m per joint: give --torque-noise or --prior)"
    bool noise_known = false;
    std::vector<std::string> fallbacks;  // --prior's parameters not identified there
};

// --prior FILE (may be empty) and --torque-noise (empty, one value, or one per joint; it overrides the prior's noise).
ExcitePrior resolve_prior(const robot::RobotDescription& robot, const robot::RobotModel& model, const std::string& prior_path,
                          const std::vector<double>& torque_noise);

// The motion of --compare FILE: a trajectory table with t, q1.., qd1.., qdd1.. (excite's CSV) as it is; any
// other log (a headered CSV with the description's columns, or --log-format) differentiated as identify
// would (its plan and Jacobi differentiators), on the samples whose derivatives are valid.
struct CompareMotion {
    excite::SampledMotion motion;
    double duration = 0.0;  // s, of the samples counted
    std::string how;        // "trajectory table" or "log, differentiated like identify (...)"
};
CompareMotion read_compare_motion(const std::string& path, const robot::RobotDescription& robot, const robot::RobotModel& model,
                                  const options::LogFormatOptions& format, bool quiet);

// One criterion figure for a predicted motion (lower is better), comparable between two motions:
// d-optimal -log det A, a-relative log sum C_kk / s_k^2, e-relative log max; cond/logdet: log of the worst relative std.
double prediction_score(excite::Criterion criterion, const excite::Prediction& p);

nlohmann::json prediction_json(const std::vector<std::string>& names, const ExcitePrior& prior, const excite::Prediction& p);

// The table of every base parameter: prior, scale, predicted std and relative std, and the comparison's.
std::string prediction_table(const std::vector<std::string>& names, const ExcitePrior& prior, const excite::Prediction& design,
                             const excite::Prediction* compare);

// --payload: the prior the payload's table and JSON show (the point mass's ten parameters and their scales; the
// noise stays the prior's).
ExcitePrior payload_prior(const ExcitePrior& prior, const excite::PayloadTarget& payload);

// --payload's JSON `payload`: the prior (mass, com, link, standard parameters, scales) and the predicted std of what
// `jacobid payload` prints (mass, com_x.., I_xx.. about the centre of mass), the design's and --compare's.
nlohmann::json payload_json(const excite::PayloadTarget& payload, const Eigen::VectorXd& inertial_std, const Eigen::VectorXd* compare_inertial_std);

// The same predicted std as a table (one line per quantity), the comparison's beside.
std::string payload_table(const Eigen::VectorXd& inertial_std, const Eigen::VectorXd* compare_inertial_std);

}  // namespace jacobid::cli
