// SPDX-License-Identifier: MIT
#include "payload/arm_file.hpp"

#include <fmt/core.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "core/errors.hpp"

namespace jacobid::payload {
namespace {

bool is_json(const std::string& path) { return path.size() >= 5 && path.compare(path.size() - 5, 5, ".json") == 0; }

double number_at(const nlohmann::json& v, const std::string& path, const std::string& key) {
    if (!v.is_number() || !std::isfinite(v.get<double>())) throw InputError(fmt::format("--arm {}: {}: expected a finite number, got {}", path, key, v.dump()));
    return v.get<double>();
}

void finish(ArmModel& arm) {
    arm.model = robot::make_robot_model(arm.description);
    arm.serial = dynamic_cast<const robot::SerialRobotModel*>(arm.model.get());
    if (!arm.serial) {
        throw InputError(fmt::format("--arm {}: model {} has no per-link standard parameters to carry a payload; describe the robot with model mdh or "
                                     "urdf (and no presliding friction)",
                                     arm.source, arm.model->model_name()));
    }
}

ArmModel from_json(const std::string& path, const robot::RobotDescription& robot) {
    std::ifstream in(path);
    if (!in) throw InputError(fmt::format("--arm {}: cannot open the file", path));
    nlohmann::json j;
    try {
        j = nlohmann::json::parse(in);
    } catch (const nlohmann::json::parse_error& e) {
        throw InputError(fmt::format("--arm {}: not JSON (expected `jacobid identify --format json` output): {}", path, e.what()));
    }
    if (!j.is_object() || !j.contains("parameters") || !j["parameters"].is_object()) {
        throw InputError(fmt::format("--arm {}: no `parameters` object (expected `jacobid identify --format json` output)", path));
    }
    ArmModel arm;
    arm.source = path;
    arm.base_only = true;
    arm.description = robot;
    const std::size_t n = robot.joints.size();
    // The smoothing the arm was identified with: its parameters belong to those FCj columns.
    if (j.contains("coulomb_smoothing") && j["coulomb_smoothing"].contains("joints")) {
        const auto& joints = j["coulomb_smoothing"]["joints"];
        if (!joints.is_array() || joints.size() != n) {
            throw InputError(fmt::format("--arm {}: coulomb_smoothing.joints: expected {} entries (the joints of --robot {})", path, n, robot.source));
        }
        arm.description.coulomb_alpha.clear();
        for (std::size_t k = 0; k < n; ++k) {
            arm.description.coulomb_alpha.push_back(number_at(joints[k]["alpha"], path, fmt::format("coulomb_smoothing.joints[{}].alpha", k)));
        }
    }
    arm.description.coulomb_alpha_auto = false;
    finish(arm);
    const std::vector<std::string>& names = arm.model->parameter_names();
    arm.values = robot::true_parameters(arm.description, *arm.model);
    arm.std_dev = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(names.size()));
    const auto& parameters = j["parameters"];
    for (std::size_t k = 0; k < names.size(); ++k) {
        if (!parameters.contains(names[k])) {
            throw InputError(fmt::format("--arm {}: parameters.{}: missing (the model of --robot {} has this base parameter; identified with another "
                                         "description?)",
                                         path, names[k], robot.source));
        }
        const auto& e = parameters[names[k]];
        const bool identified = e.is_object() && e.contains("value") && !e["value"].is_null() &&
                                (!e.contains("identified") || (e["identified"].is_boolean() && e["identified"].get<bool>()));
        if (!identified) {
            arm.fallbacks.push_back(names[k]);
            continue;
        }
        const auto k_ = static_cast<Eigen::Index>(k);
        arm.values[k_] = number_at(e["value"], path, "parameters." + names[k] + ".value");
        if (e.contains("std") && !e["std"].is_null()) arm.std_dev[k_] = number_at(e["std"], path, "parameters." + names[k] + ".std");
    }
    if (j.contains("torque_delay") && j["torque_delay"].contains("applied_seconds")) {
        arm.torque_delay = number_at(j["torque_delay"]["applied_seconds"], path, "torque_delay.applied_seconds");
    }
    return arm;
}

ArmModel from_description(const std::string& path, const robot::RobotDescription& robot) {
    ArmModel arm;
    arm.source = path;
    arm.description = robot::load_robot_description(path);
    if (arm.description.joints.size() != robot.joints.size()) {
        throw InputError(fmt::format("--arm {}: {} joints, but --robot {} has {}", path, arm.description.joints.size(), robot.source, robot.joints.size()));
    }
    // An exported description fixes its smoothing; one left at auto is read with its coulomb.alpha, as simulate does.
    arm.description.coulomb_alpha_auto = false;
    finish(arm);
    arm.values = robot::true_parameters(arm.description, *arm.model);
    return arm;
}

}  // namespace

ArmModel load_arm(const std::string& path, const robot::RobotDescription& robot) {
    return is_json(path) ? from_json(path, robot) : from_description(path, robot);
}

}  // namespace jacobid::payload
