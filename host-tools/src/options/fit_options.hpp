// SPDX-License-Identifier: MIT
#pragma once
// The options that say how a log is identified (pipeline cutoffs, windows, decimation, torque delay,
// weighting), registered alike by `jacobid identify` and `jacobid montecarlo`, so that a Monte Carlo study
// takes the very options identify takes.
#include <optional>
#include <string>
#include <vector>

#include "identify/identify_run.hpp"
#include "identify/pipeline/pipeline.hpp"

namespace CLI {
class App;
class Option;
}  // namespace CLI

namespace jacobid::options {

struct FitOptions {
    identify::PipelineSettings pipeline;
    std::string discretization = "exact";
    std::string torque_delay = "auto";  // auto | seconds
    bool weighted = false;             // --weighted (kept for scripts): the same as --weighting wls
    bool unweighted = false;           // --unweighted: the same as --weighting ols
    std::string weighting = "wls";     // wls | ols
    std::string estimator;             // ols | wls | iv | didim; empty: the weighting's least squares
    const CLI::Option* weighting_option = nullptr;  // to tell an explicit --weighting from its default
    std::string std_method = "joint-hac";  // joint-hac | pooled
    double rank_tolerance = 1e-7;
    std::vector<double> joint_noise;   // --joint-noise: WLS weights 1 / noise per joint (N.m); empty: from the OLS residuals
};

// --bandwidth ... --min-motion, --torque-delay, --estimator, --weighting (--weighted, --unweighted), --joint-noise, --std, --std-lags,
// --rank-tolerance.
void add_fit_options(CLI::App* cmd, FitOptions& o);

// --bandwidth, --cutoff, --decimation-cutoff, --decimation (the pipeline's rates, also diagnose's).
void add_pipeline_rate_options(CLI::App* cmd, identify::PipelineSettings& pipeline);

// --torque-delay: nullopt for auto, else the seconds given (InputError naming the option if malformed).
std::optional<double> given_torque_delay(const FitOptions& o);

// The settings of identify::identify_log for `method` (--discretization, the estimator and the weighting resolved, --torque-delay
// parsed; InputError for contradicting options).
identify::IdentifySettings identify_settings(const FitOptions& o, identify::Method method);

// The methods of --method (jacobi, butterworth or both, in that order).
std::vector<identify::Method> methods_of(const std::string& method_option);

// The pipeline of one method: `common` with the method and --velocity applied (empty: the method's own
// differentiated velocity). InputError for a differentiated velocity of another method than `method`.
identify::PipelineSettings method_pipeline(const identify::PipelineSettings& common, identify::Method method, const std::string& velocity,
                                           const std::string& method_option);

}  // namespace jacobid::options
