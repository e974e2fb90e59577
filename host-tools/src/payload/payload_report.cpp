// SPDX-License-Identifier: MIT
#include "payload/payload_report.hpp"

#include <fmt/core.h>

#include <cmath>

#include "identify/report/json_number.hpp"

namespace jacobid::payload {
namespace {

using nlohmann::json;

using identify::finite_json;

double rel_percent(double std, double value) { return value != 0.0 ? 100.0 * std / std::abs(value) : std::nan(""); }

// The status of an output quantity: known (the mass given), prior when any standard parameter it is made of was
// fixed to the prior (inertia entries from the inertias, centre of mass from the first moments), else identified.
const char* inertial_status(const PayloadEstimate& e, int k) {
    if (k == 0) return to_string(e.status[9]);
    const int first = k <= 3 ? 6 : 0, count = k <= 3 ? 3 : 6;
    for (int i = first; i < first + count; ++i) {
        if (e.status[i] == Status::Prior) return "prior";
    }
    return "identified";
}

}  // namespace

std::string payload_text(const PayloadEstimate& e) {
    std::string t;
    t += fmt::format("payload on the last link, from {}{} (arm held at {})\n", e.loaded_source,
                     e.unloaded_source.empty() ? "" : " minus the unloaded run " + e.unloaded_source + " (residuals against the arm, row by row)",
                     e.arm_source);
    if (e.alignment) {
        t += fmt::format("time alignment: unloaded run shifted by {:+.4f} s (resolution {:.2g} ms), positions then differ by {:.3g} rad RMS (motion "
                         "{:.3g} rad RMS); {} samples of the loaded run used\n",
                         e.alignment->shift, 1e3 * e.alignment->resolution, e.alignment->position_rms, e.alignment->motion_rms,
                         e.alignment->last - e.alignment->first);
    }
    t += fmt::format("pipeline: bandwidth {:.3g} Hz, F_p {:.3g} Hz, decimation {}, {} equations, {}; {}\n", e.info.bandwidth, e.info.decimation_cutoff,
                     e.info.decimation, e.solution.equations, e.solution.weighted ? "wls" : "ols",
                     e.delay_from_arm ? fmt::format("torque delay {:+.3f} ms (the arm's identification's)", 1e3 * e.delay.applied()) : identify::describe(e.delay));
    t += fmt::format("frame: {}\n\n", e.frame_name);
    t += fmt::format("{:<8} {:>12} {:>11} {:>8} {:>11} {:>11} {:>11}  {}\n", "", "value", "std", "%sigma", "noise std", "arm std", "gain std", "status");
    const char* units[10] = {"kg", "m", "m", "m", "kg.m^2", "kg.m^2", "kg.m^2", "kg.m^2", "kg.m^2", "kg.m^2"};
    const Inertial10 v = flatten(e.inertial);
    for (int k = 0; k < 10; ++k) {
        t += fmt::format("{:<8} {:>12.5g} {:>11.3g} {:>8.2f} {:>11.3g} {:>11.3g} {:>11.3g}  {} {}\n", inertial_names()[static_cast<std::size_t>(k)], v[k],
                         e.std_total[k], rel_percent(e.std_total[k], v[k]), e.std_noise[k], e.std_arm[k], e.std_gain[k], inertial_status(e, k), units[k]);
    }
    t += "\nstandard parameters about the last link's frame (what the regressor sees):";
    for (int k = 0; k < 10; ++k) t += fmt::format(" {}={:.5g}", standard_names()[static_cast<std::size_t>(k)], e.standard[k]);
    t += "\nstd includes: ";
    for (std::size_t i = 0; i < e.included.size(); ++i) t += (i ? "; " : "") + e.included[i];
    t += "\n";
    if (!e.left_out.empty()) {
        t += "std leaves out: ";
        for (std::size_t i = 0; i < e.left_out.size(); ++i) t += (i ? "; " : "") + e.left_out[i];
        t += "\n";
    }
    t += "mass change per +1 % drive gain:";
    for (std::size_t j = 0; j < e.mass_gain_sensitivity.size(); ++j) t += fmt::format(" J{} {:+.3g} kg", j + 1, 0.01 * e.mass_gain_sensitivity[j]);
    t += "\n";
    for (const auto& u : e.unidentifiable) {
        std::string combo;
        for (std::size_t i = 0; i < u.parameters.size(); ++i) combo += fmt::format("{}{:+.3g} {}", i ? " " : "", u.coefficients[i], e.solution.names[static_cast<std::size_t>(u.parameters[i])]);
        t += "not identifiable: " + combo + "\n";
    }
    const bool inertia_prior = std::string(inertial_status(e, 4)) == "prior";
    t += !e.violations.empty() ? "physical consistency: FAILS\n"
         : inertia_prior       ? "physical consistency: mass > 0 (the inertia is the point-mass prior, not checked)\n"
                               : "physical consistency: mass > 0, inertia about the centre of mass positive definite, triangle inequalities hold\n";
    for (const auto& w : e.warnings) t += "warning: " + w + "\n";
    return t;
}

json payload_json(const PayloadEstimate& e) {
    json j;
    j["loaded"] = e.loaded_source;
    j["unloaded"] = e.unloaded_source.empty() ? json(nullptr) : json(e.unloaded_source);
    j["arm"] = e.arm_source;
    j["frame"] = e.frame_name;
    const Eigen::Vector3d p = e.tool.translation();
    const Eigen::Vector3d rpy = e.tool.linear().eulerAngles(2, 1, 0).reverse();
    j["tool_frame"] = {{"xyz", {p.x(), p.y(), p.z()}}, {"rpy", {rpy.x(), rpy.y(), rpy.z()}}};
    const Inertial10 v = flatten(e.inertial);
    json q = json::object();
    for (int k = 0; k < 10; ++k) {
        q[inertial_names()[static_cast<std::size_t>(k)]] = {{"value", v[k]},
                                                             {"std", finite_json(e.std_total[k])},
                                                             {"rel_std_percent", finite_json(rel_percent(e.std_total[k], v[k]))},
                                                             {"std_noise", finite_json(e.std_noise[k])},
                                                             {"std_arm", finite_json(e.std_arm[k])},
                                                             {"std_gain", finite_json(e.std_gain[k])},
                                                             {"status", inertial_status(e, k)}};
    }
    j["payload"] = q;
    json s = json::object();
    const Eigen::VectorXd sd = e.covariance().diagonal().cwiseMax(0.0).cwiseSqrt();
    for (int k = 0; k < 10; ++k) {
        s[standard_names()[static_cast<std::size_t>(k)]] = {{"value", e.standard[k]}, {"std", sd[k]}, {"status", to_string(e.status[k])}};
    }
    j["standard_parameters"] = s;
    json un = json::array();
    for (const auto& u : e.unidentifiable) {
        json names = json::array();
        for (int k : u.parameters) names.push_back(e.solution.names[static_cast<std::size_t>(k)]);
        un.push_back({{"parameters", names}, {"coefficients", u.coefficients}});
    }
    j["unidentifiable"] = un;
    j["std_includes"] = e.included;
    j["std_leaves_out"] = e.left_out;
    j["mass_per_relative_gain"] = e.mass_gain_sensitivity;
    j["physically_consistent"] = e.violations.empty();
    j["violations"] = e.violations;
    j["warnings"] = e.warnings;
    j["equations"] = e.solution.equations;
    j["weighting"] = e.solution.weighted ? "wls" : "ols";
    j["std_method"] = identify::to_string(e.solution.std_method);
    j["relative_error_norm"] = finite_json(e.solution.relative_error_norm);
    j["settings"] = {{"bandwidth_hz", e.info.bandwidth}, {"decimation_cutoff_hz", e.info.decimation_cutoff}, {"decimation", e.info.decimation},
                     {"torque_delay_applied_seconds", e.delay.applied()}, {"torque_delay_from_arm", e.delay_from_arm}};
    if (e.alignment) {
        j["alignment"] = {{"shift_seconds", e.alignment->shift},
                          {"resolution_seconds", e.alignment->resolution},
                          {"position_rms_rad", e.alignment->position_rms},
                          {"motion_rms_rad", e.alignment->motion_rms},
                          {"loaded_samples_used", e.alignment->last - e.alignment->first}};
    }
    return j;
}

}  // namespace jacobid::payload
