// SPDX-License-Identifier: MIT
#include "excite/prior_file.hpp"

#include <fmt/core.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/errors.hpp"

namespace jacobid::excite {
namespace {

double finite_number(const nlohmann::json& v, const std::string& path, const std::string& key, bool positive) {
    if (!v.is_number()) throw InputError(fmt::format("{}: {}: expected a number, got {}", path, key, v.dump()));
    const double x = v.get<double>();
    if (!std::isfinite(x) || (positive && !(x > 0.0))) throw InputError(fmt::format("{}: {}: expected a finite number{}, got {}", path, key, positive ? " > 0" : "", x));
    return x;
}

}  // namespace

PriorFile read_prior_file(const std::string& path, const robot::RobotModel& model, const Eigen::VectorXd& description_values) {
    std::ifstream in(path);
    if (!in) throw InputError(fmt::format("--prior {}: cannot open the file", path));
    nlohmann::json j;
    try {
        j = nlohmann::json::parse(in);
    } catch (const nlohmann::json::parse_error& e) {
        throw InputError(fmt::format("--prior {}: not JSON (expected `jacobid identify --format json` output): {}", path, e.what()));
    }
    if (!j.is_object() || !j.contains("parameters") || !j["parameters"].is_object()) {
        throw InputError(fmt::format("--prior {}: no `parameters` object (expected `jacobid identify --format json` output)", path));
    }
    PriorFile p;
    const auto& names = model.parameter_names();
    p.values = description_values;
    const auto& parameters = j["parameters"];
    for (std::size_t k = 0; k < names.size(); ++k) {
        if (!parameters.contains(names[k])) {
            throw InputError(fmt::format("--prior {}: parameters.{}: missing (the robot description's model has this base parameter; was the file "
                                         "identified with another description?)",
                                         path, names[k]));
        }
        const auto& entry = parameters[names[k]];
        const auto value = entry.is_object() && entry.contains("value") ? entry["value"] : nlohmann::json();
        const bool identified = !entry.contains("identified") || (entry["identified"].is_boolean() && entry["identified"].get<bool>());
        if (value.is_null() || !identified) {
            p.fallbacks.push_back(names[k]);
            continue;
        }
        p.values[static_cast<Eigen::Index>(k)] = finite_number(value, path, "parameters." + names[k] + ".value", false);
    }
    const int n = model.joint_count();
    if (!j.contains("joint_sigma") || !j["joint_sigma"].is_array() || static_cast<int>(j["joint_sigma"].size()) != n) {
        throw InputError(fmt::format("--prior {}: joint_sigma: expected a list of {} per-joint residual stds (N.m)", path, n));
    }
    double decimation = 1.0;
    if (j.contains("settings") && j["settings"].is_object() && j["settings"].contains("decimation")) {
        decimation = finite_number(j["settings"]["decimation"], path, "settings.decimation", true);
    }
    const bool factors = j.contains("joint_long_run_factors") && j["joint_long_run_factors"].is_array();
    if (factors && static_cast<int>(j["joint_long_run_factors"].size()) != n) {
        throw InputError(fmt::format("--prior {}: joint_long_run_factors: expected {} values, got {}", path, n, j["joint_long_run_factors"].size()));
    }
    p.noise_std.resize(n);
    for (int a = 0; a < n; ++a) {
        const double sigma = finite_number(j["joint_sigma"][static_cast<std::size_t>(a)], path, fmt::format("joint_sigma[{}]", a), true);
        const double f = factors ? finite_number(j["joint_long_run_factors"][static_cast<std::size_t>(a)], path, fmt::format("joint_long_run_factors[{}]", a), true) : 1.0;
        p.noise_std[a] = sigma * std::sqrt(decimation * f);
    }
    return p;
}

}  // namespace jacobid::excite
