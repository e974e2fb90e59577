// SPDX-License-Identifier: MIT
#pragma once
// The identify job: one or several logs identified with every feature of `jacobid identify` (pieces, gaps,
// --period, --physical, --essential, the estimators, validation, the identifiability warnings, the model export
// and the report), from options to results and their JSON / text. The command line parses and prints
// (cli/identify_command.cpp); the Python module's jacobid.identify() calls the same job, so both give the same
// numbers and the same layout. --drive-gains is options/drive_gains_options.hpp's run.
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "identify/plan/periodic_log.hpp"
#include "identify/report/report.hpp"
#include "job/identify_inputs.hpp"
#include "options/identify_options.hpp"
#include "options/output_file.hpp"
#include "robot/robot_description.hpp"
#include "robot/robot_model.hpp"

namespace jacobid::job {

struct IdentifyJobResult {
    std::vector<identify::MethodResult> results;  // one per method of --method, in its order
    identify::ReportContext ctx;                  // log, model and joint names, truth, warnings
    std::unique_ptr<identify::PeriodicLog> periodic;  // --period: the averaged period
    std::optional<nlohmann::json> exported;       // --export-urdf / --export-robot: what was written
    std::vector<std::string> inputs;              // the --in names
    std::string model_name;
    double parse_seconds = 0.0;
};

// --threads resolved (0: one per core; InputError below 0) into the pipeline, and the fit plots' rows kept only
// for --report. Idempotent; run_identify calls it too.
void resolve_threads(options::IdentifyOptions& o);

// The files the job reads and writes, checked before any work (options/output_file.hpp, check_outputs); the
// caller's own outputs (--output) in `outputs`.
void check_identify_files(const options::IdentifyOptions& o, const robot::RobotDescription& robot, std::vector<options::NamedPath> outputs);

// Identifies `logs` (one per o.inputs) with each method of --method; `validation` is --validate's log, `truth`
// the true parameters by name (already checked to be the model's). Prints warnings and progress on stderr
// (unless --quiet), writes --export-urdf / --export-robot and --report. InputError for every refused
// combination, a bad log, a non-finite solution.
IdentifyJobResult run_identify(const robot::RobotDescription& robot, const robot::RobotModel& model, options::IdentifyOptions o,
                               std::vector<LogSource> logs, std::optional<LogSource> validation, std::map<std::string, double> truth);

// What follows a method's least squares: --physical, --essential, then `validate_fit` (may be empty) with the
// model fitted. The several-log path of run_identify and jacobid.merge (python/src/fleet_bindings.cpp) share it.
void complete_fit(identify::IdentifiedLog& fit, const robot::RobotDescription& robot, const robot::RobotModel& model, const options::IdentifyOptions& o,
                  const identify::SolveOptions& solve, const std::function<void(const robot::RobotModel&, identify::MethodResult&)>& validate_fit);

// The end of a run with every method's result in `out`: the identifiability warnings (into out.ctx, then every
// warning on stderr), the finite-solution check, --export-urdf / --export-robot and --report.
void finish_identify(IdentifyJobResult& out, const robot::RobotDescription& robot, const options::IdentifyOptions& o);

// The report's context (log and joint names, truth, the period's warnings, a validation that is the --in log).
identify::ReportContext report_context(const robot::RobotDescription& robot, const robot::RobotModel& model, const options::IdentifyOptions& o,
                                       std::map<std::string, double> truth, const identify::PeriodicLog* periodic, bool validation_is_file);

// `jacobid identify --format json`'s layout: the first method at the top level, every method under "methods",
// and log, logs, model, parse_seconds, export, period.
nlohmann::json to_json(const IdentifyJobResult& r);
// The text output (Table II per method, the period's and the export's lines).
std::string to_text(const IdentifyJobResult& r);

}  // namespace jacobid::job
