// SPDX-License-Identifier: MIT
#include "job/identify_job.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <functional>
#include <cmath>
#include <thread>

#include "core/errors.hpp"
#include "identify/friction/coulomb_smoothing.hpp"
#include "identify/identify_run.hpp"
#include "identify/solve/least_squares.hpp"
#include "identify/physical/physical_identification.hpp"
#include "identify/pipeline/pipeline.hpp"
#include "identify/physical/plausibility.hpp"
#include "identify/validation/segmented_validation.hpp"
#include "identify/validation/static_validation.hpp"
#include "identify/friction/torque_delay.hpp"
#include "identify/validation/validate_log.hpp"
#include "identify/validation/validation.hpp"
#include "io/distinct_inputs.hpp"
#include "job/identify_plan.hpp"
#include "options/model_export_options.hpp"
#include "options/robot_files.hpp"

namespace jacobid::job {

using namespace jacobid::options;

namespace {

// --period: the log averaged over its periods (periodic_log.hpp), described on stderr unless the text output,
// which starts with the same line, goes to the terminal.
std::unique_ptr<identify::PeriodicLog> periodic_log(const InputLogs& inputs, const IdentifyOptions& o, const identify::IdentifySettings& settings) {
    if (o.period.empty()) return nullptr;
    if (o.inputs.size() > 1) throw InputError(fmt::format("--period with {} --in logs: periods are averaged over one continuous log", o.inputs.size()));
    if (inputs.split()) throw InputError(fmt::format("--period with --on-gap split: {} has gaps; periods are averaged over one continuous log", o.first_input()));
    if (identify::is_iterated(settings.estimator.estimator)) {
        throw InputError(fmt::format("--period with --estimator {}: the estimator simulates the log itself, not its mean period (use wls or ols)",
                                     identify::to_string(settings.estimator.estimator)));
    }
    auto periodic = identify::average_periods(inputs.columns.front(), identify::parse_period_option(o.period), o.pipeline.min_joint_motion);
    if (!o.quiet && !o.text_on_stdout) fmt::print(stderr, "identify: {}\n", identify::describe(*periodic));
    return periodic;
}

// --physical / --semi-physical as solver settings; nullopt for neither. InputError for both, or a bad weight.
std::optional<identify::PhysicalSettings> physical_settings(const IdentifyOptions& o) {
    if (o.physical && o.semi_physical) throw InputError("--physical and --semi-physical: give one of them");
    if (!(o.prior_weight >= 0.0) || !std::isfinite(o.prior_weight)) {
        throw InputError(fmt::format("--prior-weight {}: expected a finite weight >= 0", o.prior_weight));
    }
    if (!o.physical && !o.semi_physical) return std::nullopt;
    identify::PhysicalSettings s;
    s.constraint = o.physical ? identify::PhysicalConstraint::Full : identify::PhysicalConstraint::Semi;
    s.prior_weight = o.prior_weight;
    return s;
}

// The combinations of a method's estimator with the other options that cannot work, refused before the method runs.
void refuse_estimator_combinations(const identify::IdentifySettings& resolved, const InputLogs& inputs, bool pieces,
                                   const std::optional<identify::PhysicalSettings>& physical, const IdentifyOptions& o) {
    const identify::Estimator estimator = resolved.estimator.estimator;
    if (identify::is_iterated(estimator) && pieces) {
        throw InputError(inputs.several() ? fmt::format("--estimator {} with {} --in logs: the estimator simulates one continuous log",
                                                        identify::to_string(estimator), o.inputs.size())
                                          : fmt::format("--estimator {}: {} is split at its gaps (--on-gap split); the estimator simulates one continuous log",
                                                        identify::to_string(estimator), o.first_input()));
    }
    if (identify::is_iterated(estimator) && physical) {
        throw InputError(fmt::format("--{} with --estimator {}: the physically consistent fit is a least-squares one (use wls or ols)",
                                     identify::to_string(physical->constraint), identify::to_string(estimator)));
    }
    if (estimator == identify::Estimator::Iv && o.essential_flag) {
        throw InputError("--essential with --estimator iv: the essential parameters are chosen by least squares (use wls or didim)");
    }
}

// Every segment or log with the choices resolved on the longest one, the equations stacked (segmented_pipeline.hpp):
// the delay with the description's alpha, then each joint's alpha (friction alpha: auto) on the aligned log.
identify::IdentifiedLog identify_pieces(InputLogs& inputs, const robot::RobotDescription& robot, const robot::RobotModel& model,
                                        const identify::PipelineSettings& settings, const identify::SolveOptions& solve, const IdentifyOptions& o,
                                        std::optional<identify::ShiftedTorques>& first_aligned) {
    const std::vector<identify::LogColumns>& logs = inputs.columns;
    identify::SegmentSource source;
    if (inputs.several()) source = {"--in", "log"};
    if (inputs.in_pieces()) source = {"--piece-rows", "piece"};
    if (inputs.in_pieces() && logs.front().q.empty()) read_first_piece_again(inputs, robot, o);  // freed by the method before
    // Plan -> factor per log -> merge -> solve, the pieces jacobid.plan / factor / merge run (identify_plan.hpp).
    MethodPlan plan = plan_method(logs, source, robot, model, settings, solve, given_torque_delay(o), [&](double delay) {
        if (!inputs.in_pieces()) return;
        // A log read piece by piece: its first piece is read again for a further method, so its torques,
        // read by nothing else now, are aligned in place (every later piece's are, by the pipeline),
        // not into a copy beside the piece (173 MB for an hour of 6-axis torques).
        identify::LogColumns& first = inputs.columns.front();
        first.own_tau = identify::writable_torques(inputs.read.front().tables.front(), first);
        first_aligned = identify::shift_torques(first, delay);  // holds no copy: in place
        first = first_aligned->log;
    });
    std::vector<identify::SegmentReport> piece_lines = inputs.pieces;
    std::vector<std::string> piece_names = inputs.names;
    const identify::NextSegment more =
        inputs.in_pieces() ? inputs.streamed->rest(logs.front().sample_period, piece_lines, piece_names, [&] { release_first_piece(inputs); }) : nullptr;
    identify::SegmentedOutput split =
        identify::run_segmented_pipeline(plan.smoothed.get(model), logs, plan.segments, plan.delay.applied(), o.threads, more);
    return solve_plan(std::move(plan), std::move(split), std::move(piece_lines), piece_names, model, solve);
}

// --validate: one log (or a log that holds a pose) as identify::validate_log does it; with --on-gap split, the
// torques predicted through the identification's filters, pooled over the segments.
void validate(const robot::RobotModel& model, const LogSegments& input, const std::vector<identify::LogColumns>& logs,
              const identify::PipelineSettings& settings, const IdentifyOptions& o, identify::MethodResult& r) {
    const bool holds_pose = std::any_of(logs.begin(), logs.end(), [&](const auto& l) { return identify::is_static(l, o.pipeline.min_joint_motion); });
    if (holds_pose && logs.size() > 1) {
        throw InputError(fmt::format("--validate {}: --on-gap split cut a log that holds a pose into {} segments; the static check needs one "
                                     "(use --on-gap interpolate)", o.validate, logs.size()));
    }
    if (holds_pose || !input.split) {
        identify::validate_log(model, logs.front(), settings, o.pipeline.min_joint_motion, r);
        return;
    }
    // The same hardware, the same offset between its channels.
    std::vector<identify::ShiftedTorques> aligned;
    aligned.reserve(logs.size());
    std::vector<identify::LogColumns> views;
    for (const auto& l : logs) views.push_back(aligned.emplace_back(identify::shift_torques(l, r.torque_delay.applied())).log);
    const identify::PipelineSettings v = identify::validation_settings(settings, r.info);
    identify::SegmentedValidation pooled = identify::validate_segments(model, views, v, r.solution.x, o.validate);
    r.validation = std::move(pooled.result);
    r.validation_segments = segment_reports(input.segments, pooled.used, pooled.why, identify::to_string(r.info.method), o.validate);
}

}  // namespace

identify::ReportContext report_context(const robot::RobotDescription& robot, const robot::RobotModel& model, const IdentifyOptions& o,
                                       std::map<std::string, double> truth, const identify::PeriodicLog* periodic, bool validation_is_file) {
    identify::ReportContext ctx;
    ctx.log_source = log_names(o.inputs);
    ctx.model_name = model.model_name();
    for (const auto& j : robot.joints) ctx.joint_names.push_back(j.name);
    ctx.truth = std::move(truth);
    if (periodic) ctx.warnings.insert(ctx.warnings.end(), periodic->warnings.begin(), periodic->warnings.end());
    for (const std::string& in : validation_is_file ? o.inputs : std::vector<std::string>{}) {  // a validation that validates nothing
        const std::string why = io::same_log(in, o.validate);
        if (!why.empty()) ctx.warnings.push_back(fmt::format("--validate {} is the --in log ({}): its validation figures are in-sample", o.validate, why));
    }
    return ctx;
}


void resolve_threads(IdentifyOptions& o) {
    if (o.threads < 0) throw InputError(fmt::format("--threads {}: must be >= 0 (0: one per core)", o.threads));
    if (o.threads == 0) o.threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    o.pipeline.threads = o.threads;  // one log: its regressor, F_p and QR on every thread (several: see run_segmented_pipeline)
    // The decimated rows kept for the fit plots only serve --report (20 000 rows of 6 x 53 columns: 51 MB).
    if (o.report.empty()) o.pipeline.plot_rows = 0;
}

void check_identify_files(const IdentifyOptions& o, const robot::RobotDescription& robot, std::vector<NamedPath> outputs) {
    std::vector<NamedPath> read_files = robot_files("--robot", o.robot, robot);
    read_files.insert(read_files.end(), {{"--truth", o.truth}, {"--validate", o.validate}, {"--can-config", o.can_config},
                                         {"--log-format", o.log_format.file}, {"--loaded", o.drive_gains.loaded}});
    for (const std::string& in : o.inputs) read_files.push_back({"--in", in});
    outputs.insert(outputs.end(), {{"--export-urdf", o.model_export.urdf}, {"--export-robot", o.model_export.robot}});
    check_outputs(outputs, read_files);
    if (o.report.empty()) return;
    read_files.insert(read_files.end(), outputs.begin(), outputs.end());
    check_output_directory({"--report", o.report}, read_files);  // written after the work: checked before it
}

IdentifyJobResult run_identify(const robot::RobotDescription& robot, const robot::RobotModel& model, IdentifyOptions o, std::vector<LogSource> logs,
                               std::optional<LogSource> validation, std::map<std::string, double> truth) {
    using Clock = std::chrono::steady_clock;
    if (logs.empty()) throw InputError("--in is required (a log to identify from)");
    resolve_threads(o);
    // Refused before the (long) identification; exporting needs standard parameters: --physical unless --semi-physical.
    identify::check_model_export(o.model_export, robot);
    o.physical = o.physical || (o.model_export.any() && !o.semi_physical);
    const std::optional<identify::PhysicalSettings> physical = physical_settings(o);
    IdentifyJobResult out;
    out.inputs = o.inputs;
    out.model_name = model.model_name();
    const auto parse_start = Clock::now();
    const bool validation_is_file = validation && !validation->table;
    InputLogs inputs = read_inputs(std::move(logs), robot, o);
    // Several pieces (segments of a log cut at its gaps, several logs, or both) are identified together.
    const bool pieces = inputs.split() || inputs.several() || inputs.in_pieces();
    out.periodic = periodic_log(inputs, o, options::identify_settings(o, identify::Method::Jacobi));
    out.parse_seconds = std::chrono::duration<double>(Clock::now() - parse_start).count();
    std::size_t samples = 0;
    for (const auto& l : inputs.columns) samples += l.samples();
    if (inputs.in_pieces()) samples = inputs.streamed->estimated_rows();
    o.pipeline.progress = !o.quiet && samples > 500'000;
    if (o.pipeline.progress) {
        fmt::print(stderr, "identify: read {} rows of {} in {:.2f} s{}\n", inputs.columns.front().samples(), log_names(o.inputs), out.parse_seconds,
                   inputs.in_pieces() ? fmt::format(" (its first piece: about {} rows in all, read piece by piece)", samples) : std::string());
    }
    LogSegments validation_input;
    std::vector<identify::LogColumns> validation_logs;
    if (validation) {
        validation_input = read_log(std::move(*validation), robot, o);
        validation_logs = columns_of(validation_input, robot, o);
    }
    out.ctx = report_context(robot, model, o, std::move(truth), out.periodic.get(), validation_is_file);
    const std::vector<identify::Method> methods = methods_of(o.method);
    for (const identify::Method m : methods) {
        identify::PipelineSettings settings = method_pipeline(o.pipeline, m, o.velocity, o.method);
        const identify::IdentifySettings resolved = options::identify_settings(o, m);
        identify::SolveOptions solve = resolved.solve;
        if (out.periodic) {
            settings = identify::periodic_settings(settings, *out.periodic);
            if (solve.joint_noise.empty()) solve.joint_noise = out.periodic->torque_noise;  // --joint-noise first
        }
        refuse_estimator_combinations(resolved, inputs, pieces, physical, o);
        identify::IdentifiedLog fit;
        std::optional<identify::ShiftedTorques> first_aligned;  // what the first piece's torques are read from
        if (pieces) {
            fit = identify_pieces(inputs, robot, model, settings, solve, o, first_aligned);
        } else {
            // One method reads the log's torques once: they are aligned in place rather than copied.
            identify::LogColumns view = out.periodic ? out.periodic->columns : inputs.columns.front();
            if (!out.periodic && methods.size() == 1) view.own_tau = identify::writable_torques(inputs.read.front().tables.front(), view);
            fit = identify::identify_log(robot, model, view, {settings, solve, given_torque_delay(o), resolved.estimator});
        }
        complete_fit(fit, robot, model, o, solve, [&](const robot::RobotModel& fitted, identify::MethodResult& r) {
            if (validation) validate(fitted, validation_input, validation_logs, settings, o, r);
        });
        out.results.push_back(std::move(fit.result));
    }
    finish_identify(out, robot, o);
    return out;
}

void complete_fit(identify::IdentifiedLog& fit, const robot::RobotDescription& robot, const robot::RobotModel& model, const IdentifyOptions& o,
                  const identify::SolveOptions& solve, const std::function<void(const robot::RobotModel&, identify::MethodResult&)>& validate_fit) {
    const std::optional<identify::PhysicalSettings> physical = physical_settings(o);
    if (physical) identify::make_physically_consistent(fit, robot, model, *physical);
    const robot::RobotModel& fitted = fit.smoothed.get(model);
    identify::MethodResult& r = fit.result;
    if (o.essential_flag) r.essential = identify::essential_parameters(fit.factors, fitted.parameter_names(), o.essential, solve);
    if (validate_fit) validate_fit(fitted, r);
}

void finish_identify(IdentifyJobResult& out, const robot::RobotDescription& robot, const IdentifyOptions& o) {
    identify::ReportContext& ctx = out.ctx;
    for (const auto& r : out.results) {
        for (const auto& w : identify::identifiability_warnings(r, ctx.joint_names)) ctx.warnings.push_back(fmt::format("[{}] {}", identify::to_string(r.info.method), w));
    }
    for (const auto& w : ctx.warnings) fmt::print(stderr, "jacobid identify: warning: {}\n", w);
    for (const auto& r : out.results) identify::require_finite_solution(r.solution, o.first_input());
    if (o.model_export.any()) out.exported = write_model_export(o.model_export, robot, out.results.front(), o.first_input());
    if (!o.report.empty()) identify::write_report(o.report, out.results, ctx);
}

nlohmann::json to_json(const IdentifyJobResult& r) {
    // One layout whatever --method: every method under "methods" (what scripts should read), and the first
    // method's fields also at the top level, as single-method output always had them.
    nlohmann::json j = identify::to_json(r.results.front(), r.ctx);
    for (const auto& m : r.results) j["methods"][identify::to_string(m.info.method)] = identify::to_json(m, r.ctx);
    j["log"] = log_names(r.inputs);
    j["logs"] = r.inputs;
    j["model"] = r.model_name;
    j["parse_seconds"] = r.parse_seconds;
    if (r.exported) j["export"] = *r.exported;
    if (r.periodic) j["period"] = identify::to_json(*r.periodic);
    return j;
}

std::string to_text(const IdentifyJobResult& r) {
    return (r.periodic ? identify::describe(*r.periodic) + "\n\n" : "") + identify::format_table(r.results, r.ctx) +
           (r.exported ? identify::describe_export(*r.exported) : "");
}

}  // namespace jacobid::job
