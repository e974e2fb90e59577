// SPDX-License-Identifier: MIT
#pragma once
// What identify --drive-gains prints (docs/identify.md, "Drive gains"): the usual parameter table of the
// stacked problem (base parameters, the payload's unknown parameters XXL.., the gains G1..), then per joint
// the gain (current to torque: the log format's prior gain times the identified factor) of every estimator,
// the least squares' std, and the `gains:` line of a log-format file; as JSON, the usual fields and a
// `drive_gains` block.
#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <string>

#include "identify/drive_gains/drive_gains.hpp"
#include "identify/report/report.hpp"

namespace jacobid::identify {

// The absolute gains of one estimate: prior gain x identified factor, per joint.
Eigen::VectorXd absolute_gains(const DriveGainResult& result, const DriveGainEstimate& estimate);
// "gains: [10.1, 10.7, ...]", the line a log-format file takes (docs/log-format.md).
std::string gains_line(const Eigen::VectorXd& gains);

std::string drive_gains_text(const DriveGainResult& result, const ReportContext& context);
nlohmann::json drive_gains_json(const DriveGainResult& result, const ReportContext& context);

}  // namespace jacobid::identify
