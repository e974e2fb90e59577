// SPDX-License-Identifier: MIT
#include "options/fit_options.hpp"

#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include <cmath>
#include <cstdlib>

#include "options/option_checks.hpp"
#include "core/errors.hpp"

namespace jacobid::options {

void add_fit_options(CLI::App* cmd, FitOptions& o) {
    add_pipeline_rate_options(cmd, o.pipeline);
    cmd->add_option("--velocity-window", o.pipeline.velocity_window, "Jacobi velocity window T in s (overrides --cutoff)")->check(positive_number());
    cmd->add_option("--acceleration-window", o.pipeline.acceleration_window, "Jacobi acceleration window T in s (overrides --cutoff)")
        ->check(positive_number());
    cmd->add_option("--kappa", o.pipeline.kappa, "Jacobi kappa")->check(finite_number())->capture_default_str();
    cmd->add_option("--mu", o.pipeline.mu, "Jacobi mu")->check(finite_number())->capture_default_str();
    cmd->add_option("--q", o.pipeline.q, "Jacobi truncation order q")->check(whole_number_from(0))->capture_default_str();
    cmd->add_option("--discretization", o.discretization, "Jacobi kernel discretization: exact (polynomial-exact on the grid) or trapezoidal (paper)")
        ->check(CLI::IsMember({"exact", "trapezoidal"}))
        ->capture_default_str();
    cmd->add_option("--butterworth-order", o.pipeline.butterworth_order, "order of the Butterworth prefilter")
        ->check(whole_number_from(1))
        ->capture_default_str();
    cmd->add_option("--min-motion", o.pipeline.min_joint_motion, "position range in rad below which a joint counts as not moving")
        ->check(non_negative_number())
        ->capture_default_str();
    cmd->add_option("--torque-delay", o.torque_delay,
                    "offset of the torque channel behind the positions: auto (estimated by least squares, compensated when "
                    "significant, reported with its std) or SECONDS (read the torque that much later; negative: earlier; 0: off)")
        ->capture_default_str();
    cmd->add_option("--estimator", o.estimator,
                    "ols | wls: least squares on the pipeline's rows (the same as --weighting ols | wls; default wls); "
                    "iv: IDIM-IV, instruments from a closed-loop simulation of the identified model along the log's reference; "
                    "didim: DIDIM, the regressor of that simulation (no differentiated positions). iv and didim start from the LS and "
                    "iterate until X changes by less than 1e-4 (at most 20 times); they use the WLS joint weights unless --weighting ols, "
                    "and need the log's reference (columns q_refJ, qd_refJ as jacobid simulate writes them) and the robot "
                    "description's controller (docs/method.md, \"Estimators\")")
        ->check(CLI::IsMember({"ols", "wls", "iv", "didim"}));
    o.weighting_option = cmd->add_option("--weighting", o.weighting,
                    "wls: each joint's rows weighted by 1 / sigma_j of its own OLS residual (Gautier; the default: joints whose noise "
                    "differs are not pooled), or ols (ordinary LS)")
        ->check(CLI::IsMember({"wls", "ols"}))
        ->capture_default_str();
    cmd->add_flag("--weighted", o.weighted, "the same as --weighting wls (kept for scripts)");
    cmd->add_flag("--unweighted", o.unweighted, "the same as --weighting ols");
    // The residuals' sigma also holds the model's and the pipeline's error, unevenly across the joints; a noise
    // known from elsewhere (a simulation, excite's --torque-noise) gives the weights the prediction assumes.
    cmd->add_option("--joint-noise", o.joint_noise,
                    "wls: weight each joint's rows by 1 / this torque noise std (N.m or N, one per joint) instead of 1 / sigma_j of its "
                    "OLS residual (which also holds model and pipeline error); only the ratios matter")
        ->delimiter(',')
        ->check(CLI::PositiveNumber);
    cmd->add_option("--std", o.std_method,
                    "how sigma_X is computed: joint-hac (per-joint residual variances and serial correlation of the decimated rows, "
                    "Newey-West weights; the default) or pooled (sigma_rho^2 (W^T W)^-1, rows independent)")
        ->check(CLI::IsMember({"joint-hac", "pooled"}))
        ->capture_default_str();
    cmd->add_option("--std-lags", o.pipeline.residual_lags, "lags of the residual autocorrelation for --std joint-hac")
        ->check(whole_number_in(0, 1000))
        ->capture_default_str();
    cmd->add_option("--rank-tolerance", o.rank_tolerance, "relative singular value below which the column-normalized W is rank deficient")
        ->check(number_between(0.0, 1.0))
        ->capture_default_str();
}

void add_pipeline_rate_options(CLI::App* cmd, identify::PipelineSettings& pipeline) {
    cmd->add_option("--bandwidth", pipeline.bandwidth,
                    "motion bandwidth in Hz (default: estimated from the data: 99 % of the velocity energy above the noise floor, limited by "
                    "the noise; the differentiators' widened to the measured torque's band; docs/method.md)")
        ->check(positive_number());
    cmd->add_option("--cutoff", pipeline.differentiator_cutoff,
                    "wanted cutoff of the differentiators / Butterworth prefilter in Hz (default: 10 x bandwidth, or with the bandwidth "
                    "estimated 10 x the larger of it and the torque's band)")
        ->check(positive_number());
    cmd->add_option("--decimation-cutoff", pipeline.decimation_cutoff, "cutoff of the decimation filter F_p in Hz (default: 5 x bandwidth)")
        ->check(positive_number());
    cmd->add_option("--decimation", pipeline.decimation, "decimation factor (default: fs / (4 x F_p cutoff))")->check(whole_number_from(1));
    cmd->add_option_function<std::string>(
           "--coulomb-velocity-ratio",
           [&pipeline](const std::string& value) {
               if (value == "auto") {
                   pipeline.coulomb_velocity_ratio = -1.0;
                   return;
               }
               char* end = nullptr;
               const double ratio = std::strtod(value.c_str(), &end);
               if (value.empty() || *end != '\0' || !std::isfinite(ratio) || ratio < 0.0 || ratio > 10.0) {
                   throw CLI::ValidationError("--coulomb-velocity-ratio", fmt::format("expected auto or a number in [0, 10], got '{}'", value));
               }
               pipeline.coulomb_velocity_ratio = ratio;
           },
           fmt::format("the Coulomb columns' velocity cutoff as a multiple of the differentiators' (F_q's); the columns then go "
                       "through the torque's filter like the torque. auto (default): per joint the wider of 2 or 1.5 whose position "
                       "noise stays within {:g} of the sign's transition width, else 1; 1: the other columns' velocity; 0: off "
                       "(docs/method.md)",
                       identify::kCoulombVelocityNoise))
        ->default_str("auto");
}

std::optional<double> given_torque_delay(const FitOptions& o) {
    if (o.torque_delay == "auto") return std::nullopt;
    char* end = nullptr;
    const double delay = std::strtod(o.torque_delay.c_str(), &end);
    if (o.torque_delay.empty() || *end != '\0' || !std::isfinite(delay) || std::abs(delay) > 1.0) {
        throw InputError(fmt::format("--torque-delay '{}': expected auto or a delay in seconds within +-1 s", o.torque_delay));
    }
    return delay;
}

identify::IdentifySettings identify_settings(const FitOptions& o, identify::Method method) {
    identify::IdentifySettings s;
    s.pipeline = o.pipeline;
    s.pipeline.method = method;
    s.pipeline.exact_discretization = o.discretization == "exact";
    if (o.weighted && o.unweighted) throw InputError("--weighted and --unweighted: give one of them");
    if (o.std_method == "joint-hac" && (o.pipeline.residual_lags < 0 || o.pipeline.residual_lags > 1000)) {
        throw InputError(fmt::format("--std-lags {}: expected 0 to 1000 lags", o.pipeline.residual_lags));
    }
    // --weighting's default is wls, so only --weighted with an explicit --weighting ols can be told apart.
    if (o.weighted && o.weighting == "ols") throw InputError("--weighted contradicts --weighting ols");
    std::string weighting = o.weighted ? "wls" : o.unweighted ? "ols" : o.weighting;
    if (o.estimator == "ols" || o.estimator == "wls") {
        // --estimator ols | wls is the weighting by another name: one given explicitly must agree.
        const bool explicit_weighting = o.weighted || o.unweighted || (o.weighting_option && o.weighting_option->count() > 0);
        if (explicit_weighting && weighting != o.estimator) {
            throw InputError(fmt::format("--estimator {} contradicts the weighting {} (--weighting, --weighted or --unweighted): give one of them",
                                         o.estimator, weighting));
        }
        weighting = o.estimator;
    }
    s.estimator.estimator = o.estimator.empty() ? identify::parse_estimator(weighting) : identify::parse_estimator(o.estimator);
    s.solve.weighted = weighting == "wls";
    if (!o.joint_noise.empty() && !s.solve.weighted) throw InputError("--joint-noise gives the WLS weights: it contradicts ols");
    s.solve.joint_noise = o.joint_noise;
    s.solve.std_method = o.std_method == "pooled" ? identify::StdMethod::Pooled : identify::StdMethod::JointHac;
    s.solve.rank_tolerance = o.rank_tolerance;
    s.torque_delay = given_torque_delay(o);
    return s;
}

std::vector<identify::Method> methods_of(const std::string& method_option) {
    std::vector<identify::Method> methods;
    if (method_option == "jacobi" || method_option == "both") methods.push_back(identify::Method::Jacobi);
    if (method_option == "butterworth" || method_option == "both") methods.push_back(identify::Method::Butterworth);
    return methods;
}

identify::PipelineSettings method_pipeline(const identify::PipelineSettings& common, identify::Method method, const std::string& velocity,
                                           const std::string& method_option) {
    identify::PipelineSettings settings = common;
    settings.method = method;
    settings.measured_velocity = velocity == "measured";
    if (!velocity.empty() && !settings.measured_velocity && velocity != identify::to_string(method)) {
        throw InputError(fmt::format("--velocity {} with --method {}: a differentiated velocity comes from the method's own differentiator "
                                     "(use --velocity measured, or --method {})",
                                     velocity, method_option, velocity));
    }
    return settings;
}

}  // namespace jacobid::options
