// SPDX-License-Identifier: MIT
#include "robot/base_parameter_report.hpp"

#include <fmt/core.h>

#include "robot/presliding_model.hpp"
#include "robot/serial_robot_model.hpp"

namespace jacobid::robot {
namespace {

std::string joined(const std::vector<std::string>& names) {
    std::string s;
    for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
    return s;
}

std::vector<std::string> no_effect_names(const SerialRobotModel& serial) {
    std::vector<std::string> names;
    for (int c : serial.base().no_effect) names.push_back(serial.standard_names()[static_cast<std::size_t>(c)]);
    return names;
}

}  // namespace

std::string base_parameter_text(const RobotDescription& d, const RobotModel& model) {
    const Eigen::VectorXd truth = true_parameters(d, model);
    const auto* serial = dynamic_cast<const SerialRobotModel*>(&rigid_body(model));
    std::string s = fmt::format("model {} ({}): {} joints", model.model_name(), d.source, model.joint_count());
    if (serial) s += fmt::format(", {} standard parameters", serial->standard_parameter_count());
    s += fmt::format(", {} base parameters\n", model.parameter_count());
    if (!serial) {
        s += "closed-form base parameters (no regrouping to compute):\n";
        for (int b = 0; b < model.parameter_count(); ++b) s += fmt::format("  {:<8} value {:.6g}\n", model.parameter_names()[static_cast<std::size_t>(b)], truth[b]);
        return s;
    }
    s += fmt::format("rank of W over random states (QR with column pivoting): {}\n", serial->base().pivoted_qr_rank);
    s += "base parameters = regrouped standard parameters (value from the description's parameters):\n";
    const auto relations = serial->relations();
    std::size_t width = 0;
    for (const auto& r : relations) width = std::max(width, r.size());
    for (std::size_t b = 0; b < relations.size(); ++b) s += fmt::format("  {:<{}}   value {:.6g}\n", relations[b], width, truth[static_cast<Eigen::Index>(b)]);
    for (int b = static_cast<int>(relations.size()); b < model.parameter_count(); ++b) {  // presliding levels FDj
        s += fmt::format("  {:<{}}   value {:.6g}\n", model.parameter_names()[static_cast<std::size_t>(b)], width, truth[b]);
    }
    const auto none = no_effect_names(*serial);
    if (!none.empty()) s += fmt::format("no effect on the torques (not identifiable at all): {}\n", joined(none));
    return s;
}

nlohmann::json base_parameter_json(const RobotDescription& d, const RobotModel& model) {
    const Eigen::VectorXd truth = true_parameters(d, model);
    nlohmann::json j;
    j["model"] = model.model_name();
    j["robot"] = d.source;
    j["joints"] = model.joint_count();
    nlohmann::json base = nlohmann::json::array();
    const auto* serial = dynamic_cast<const SerialRobotModel*>(&rigid_body(model));
    for (int b = 0; b < model.parameter_count(); ++b) {
        nlohmann::json entry;
        entry["name"] = model.parameter_names()[static_cast<std::size_t>(b)];
        entry["value"] = truth[b];
        if (serial && b < serial->parameter_count()) {
            nlohmann::json terms = nlohmann::json::array();
            for (int c = 0; c < serial->standard_parameter_count(); ++c) {
                const double k = serial->base().regrouping(b, c);
                if (k != 0.0) terms.push_back({{"parameter", serial->standard_names()[static_cast<std::size_t>(c)]}, {"coefficient", k}});
            }
            entry["terms"] = terms;
            entry["relation"] = serial->relations()[static_cast<std::size_t>(b)];
        }
        base.push_back(entry);
    }
    j["base_parameters"] = base;
    if (serial) {
        j["standard_parameters"] = serial->standard_names();
        j["no_effect"] = no_effect_names(*serial);
        j["pivoted_qr_rank"] = serial->base().pivoted_qr_rank;
    }
    return j;
}

}  // namespace jacobid::robot
