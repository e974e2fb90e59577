// SPDX-License-Identifier: MIT
// identify's JSON (report.hpp to_json): one function per block of the document, in the order the document
// lists them. The keys are a public format (users' scripts read them): extend, never rename.
#include <cmath>

#include "identify/physical/physical_identification.hpp"
#include "identify/report/json_number.hpp"
#include "identify/report/report.hpp"

namespace jacobid::identify {
namespace {

using nlohmann::json;

json finite_list(const std::vector<double>& values) {
    json a = json::array();
    for (double x : values) a.push_back(finite_json(x));
    return a;
}

json parameters_json(const LsSolution& sol, const ReportContext& ctx) {
    json params = json::object();
    for (std::size_t p = 0; p < sol.names.size(); ++p) {
        const auto i = static_cast<Eigen::Index>(p);
        json e;
        e["value"] = finite_json(sol.x[i]);
        e["std"] = finite_json(sol.std_dev[i]);
        e["rel_std_percent"] = finite_json(sol.rel_std_percent[i]);
        e["identified"] = static_cast<bool>(sol.identified[p]);
        if (sol.removed[p]) e["removed"] = true;
        const auto it = ctx.truth.find(sol.names[p]);
        if (it != ctx.truth.end()) e["truth"] = it->second;
        params[sol.names[p]] = e;
    }
    return params;
}

// The fit's size and quality, and how "std" was computed (least_squares.hpp StdMethod; docs/method.md "Bias
// and standard deviations").
void add_fit_statistics(json& j, const MethodResult& r) {
    const auto& sol = r.solution;
    j["cond"] = finite_json(sol.cond);
    j["equations"] = sol.equations;
    j["rank"] = sol.rank;
    j["relative_error_norm"] = sol.relative_error_norm;
    j["sigma_rho"] = sol.sigma_rho;
    j["residual_rms"] = sol.joint_residual_rms;
    j["weighted"] = sol.weighted;
    if (sol.weighted) j["joint_weights"] = sol.joint_weights;
    j["weighting"] = sol.weighted ? "wls" : "ols";
    j["std_method"] = r.estimator && r.estimator->estimator == Estimator::Iv ? "iv-sandwich" : to_string(sol.std_method);
    j["estimator"] = r.estimator ? to_string(r.estimator->estimator) : sol.weighted ? "wls" : "ols";
    if (r.estimator) {
        j["iterations"] = r.estimator->iterations;
        j["converged"] = r.estimator->converged;
        j["estimator_changes"] = r.estimator->changes;
    }
    if (sol.std_method == StdMethod::JointHac) {
        j["std_lags"] = sol.std_lags;
        j["joint_sigma"] = finite_list(sol.joint_sigma);
        j["joint_long_run_factors"] = finite_list(sol.joint_long_run_factors);
        j["joint_lag1_correlation"] = finite_list(sol.joint_lag1_correlation);
    }
}

json unidentifiable_json(const LsSolution& sol) {
    json un = json::array();
    for (const auto& u : sol.unidentifiable) {
        std::vector<std::string> names;
        for (int p : u.parameters) names.push_back(sol.names[static_cast<std::size_t>(p)]);
        un.push_back({{"parameters", names}, {"coefficients", u.coefficients}, {"zero_column", u.zero_column}});
    }
    return un;
}

json plausibility_json(const std::vector<PlausibilityViolation>& violations) {
    json implausible = json::array();
    for (const auto& v : violations) {
        implausible.push_back({{"parameter", v.name}, {"value", v.value}, {"std", v.std_dev}, {"rel_std_percent", v.rel_std_percent}, {"must_be", "non-negative"},
                               {"why", v.why}});
    }
    return implausible;
}

json static_validation_json(const StaticValidationResult& v) {
    json joints = json::array();
    for (const auto& e : v.joints) {
        joints.push_back({{"measured", e.measured},
                          {"measured_std", e.measured_std},
                          {"predicted", e.predicted},
                          {"error", e.error},
                          {"coulomb", std::isnan(e.coulomb) ? json(nullptr) : json(e.coulomb)},
                          {"within_friction", e.within_friction}});
    }
    return {{"log", v.source}, {"samples", v.samples}, {"pose", v.pose}, {"joints", joints}, {"relative_error", v.relative_error}};
}

json torque_delay_json(const TorqueDelayResult& d) {
    return {{"seconds", d.estimate.delay},      {"std", finite_json(d.estimate.std_dev)},
            {"estimated", !d.given},           {"compensated", d.estimate.compensated},
            {"at_bound", d.estimate.at_bound}, {"applied_seconds", d.applied()},
            {"samples_used", d.estimate.samples_used}};
}

json presliding_json(const PreslidingDisplacementChoice& p) {
    json joints = json::array();
    for (std::size_t k = 0; k < p.shape.joints.size(); ++k) {
        const JointShape& js = p.shape.joints[k];
        joints.push_back({{"displacement", p.displacement[k]}, {"chosen", js.chosen}, {"reason", js.reason}, {"heldout_rms", finite_list(js.heldout_rms)}});
    }
    return {{"auto", true}, {"candidates", p.candidates}, {"folds", p.shape.folds}, {"passes", p.shape.passes}, {"joints", joints}};
}

json coulomb_smoothing_json(const CoulombSmoothingChoice& c) {
    json joints = json::array();
    for (const auto& js : c.joints) {
        joints.push_back({{"alpha", js.alpha}, {"chosen", js.chosen}, {"reason", js.reason}, {"heldout_rms", finite_list(js.heldout_rms)}});
    }
    return {{"auto", true},         {"candidates", c.candidates},     {"folds", c.folds},  {"passes", c.passes},
            {"common_alpha", c.common_alpha}, {"common_score", c.common_score}, {"joints", joints}};
}

json segments_json(const std::vector<SegmentReport>& segments) {
    json a = json::array();
    for (const auto& r : segments) {
        json e = {{"first_line", r.first_line}, {"last_line", r.last_line}, {"duration_s", r.duration}, {"samples", r.samples},
                  {"used", r.used}, {"why", r.why}};
        if (!r.log.empty()) {
            e["log"] = r.log;
            e["rows"] = r.rows;
        }
        a.push_back(std::move(e));
    }
    return a;
}

// How the motion's bandwidth was estimated from the positions and the torques (plan/bandwidth.hpp).
json bandwidth_estimate_json(const BandwidthEstimate& b) {
    json joints = json::array();
    for (const auto& jb : b.joints) {
        joints.push_back({{"name", jb.name},
                          {"frequency_hz", finite_json(jb.frequency)},
                          {"energy_frequency_hz", finite_json(jb.energy_frequency)},
                          {"noise_limit_hz", finite_json(jb.noise_limit)},
                          {"noise_rms", finite_json(jb.noise_rms)},
                          {"floor_fraction", finite_json(jb.floor_fraction)},
                          {"quantization_step", jb.quantization_step},
                          {"jumps", jb.jumps},
                          {"moving", jb.moving},
                          {"used", jb.used}});
    }
    json torque_joints = json::array();
    for (const auto& jt : b.torque.joints) {
        torque_joints.push_back({{"name", jt.name},
                                 {"frequency_hz", finite_json(jt.frequency)},
                                 {"noise_rms", finite_json(jt.noise_rms)},
                                 {"floor_fraction", finite_json(jt.floor_fraction)},
                                 {"moving", jt.moving},
                                 {"used", jt.used}});
    }
    return {{"frequency_hz", finite_json(b.frequency)},         {"energy_frequency_hz", finite_json(b.energy_frequency)},
            {"noise_limit_hz", finite_json(b.noise_limit)},     {"noise_limited", b.noise_limited},
            {"jumps", b.jumps},                            {"resolution_hz", b.resolution},
            {"description", b.description},                {"joints", joints},
            {"torque_bandwidth_hz", finite_json(b.torque.frequency)},
            {"differentiator_bandwidth_hz", finite_json(b.differentiator_frequency)},
            {"torque_wider", b.torque_wider},
            {"torque_noise_limited", b.torque_noise_limited},
            {"torque_resolution_hz", b.torque.resolution},
            {"torque_highest_hz", finite_json(b.torque.highest)},
            {"torque_joints", torque_joints}};
}

json settings_json(const PipelineInfo& i) {
    json s = {{"sample_period", i.sample_period},
              {"samples", i.samples},
              {"bandwidth_hz", i.bandwidth},
              {"bandwidth_estimated", i.bandwidth_estimated},
              {"differentiator_cutoff_hz", i.differentiator_cutoff},
              {"velocity_window", i.velocity_window},
              {"acceleration_window", i.acceleration_window},
              {"velocity_cutoff_hz", i.velocity_cutoff},
              {"acceleration_cutoff_hz", i.acceleration_cutoff},
              {"prefilter_cutoff_hz", i.prefilter_cutoff},
              {"coulomb_velocity_cutoffs_hz", i.coulomb_velocity_cutoffs},
              {"decimation_cutoff_hz", i.decimation_cutoff},
              {"decimation", i.decimation},
              {"valid_first", i.first},
              {"valid_last", i.last},
              {"crop", i.crop}};
    if (i.bandwidth_estimated) s["bandwidth_estimate"] = bandwidth_estimate_json(i.bandwidth_estimate);
    return s;
}

json essential_json(const EssentialResult& essential, const ReportContext& ctx) {
    json steps = json::array();
    for (const auto& s : essential.steps) {
        steps.push_back({{"removed", s.removed}, {"removed_rel_std_percent", s.removed_rel_std}, {"relative_error_norm", s.relative_error_norm},
                         {"parameters", s.parameters}});
    }
    return {{"steps", steps}, {"final", parameters_json(essential.solution, ctx)}};
}

json validation_json(const ValidationResult& v) {
    return {{"log", v.source},
            {"samples", v.samples},
            {"rms_error", v.rms_error},
            {"raw_rms_error", v.raw_rms_error},
            {"raw_differentiator_cutoff_hz", v.raw_differentiator_cutoff},
            {"rms_torque", v.rms_torque},
            {"relative_error", v.relative_error}};
}

}  // namespace

json to_json(const MethodResult& r, const ReportContext& ctx) {
    json j;
    j["method"] = to_string(r.info.method);
    j["parameters"] = parameters_json(r.solution, ctx);
    j["parameter_order"] = r.solution.names;
    add_fit_statistics(j, r);
    j["unidentifiable"] = unidentifiable_json(r.solution);
    j["plausibility_violations"] = plausibility_json(r.violations);
    if (r.static_validation) j["static_validation"] = static_validation_json(*r.static_validation);
    j["torque_delay"] = torque_delay_json(r.torque_delay);
    if (r.presliding_displacement) j["presliding_displacement"] = presliding_json(*r.presliding_displacement);
    if (r.coulomb_smoothing) j["coulomb_smoothing"] = coulomb_smoothing_json(*r.coulomb_smoothing);
    if (r.physical) j["physical"] = physical_json(*r.physical);
    j["warnings"] = identifiability_warnings(r, ctx.joint_names);
    if (!r.segments.empty()) j["segments"] = segments_json(r.segments);
    if (!r.validation_segments.empty()) j["validation_segments"] = segments_json(r.validation_segments);
    j["settings"] = settings_json(r.info);
    const auto& i = r.info;
    j["timing_seconds"] = {{"differentiate", i.seconds_differentiate}, {"regressor_filter", i.seconds_regressor_filter}, {"ls", i.seconds_ls}};
    if (r.essential) j["essential"] = essential_json(*r.essential, ctx);
    if (r.validation) j["validation"] = validation_json(*r.validation);
    return j;
}

}  // namespace jacobid::identify
