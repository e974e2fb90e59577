// SPDX-License-Identifier: MIT
// jacobid identify: dynamic parameters of a robot from a log of joint positions and motor torques
// (Table II of the paper: X^, 2 sigma, %sigma_r), with the Jacobi pipeline, the Butterworth baseline or
// both side by side.
#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <optional>
#include <set>
#include <thread>
#include <nlohmann/json.hpp>

#include "core/free_memory.hpp"
#include "cli/command.hpp"
#include "cli/option_checks.hpp"
#include "cli/drive_gains_options.hpp"
#include "cli/fit_options.hpp"
#include "cli/log_format_options.hpp"
#include "cli/model_export_options.hpp"
#include "cli/output_file.hpp"
#include "cli/robot_files.hpp"
#include "cli/streamed_log.hpp"
#include "core/parallel_for.hpp"
#include "identify/coulomb_smoothing.hpp"
#include "identify/identify_run.hpp"
#include "identify/least_squares.hpp"
#include "identify/log_columns.hpp"
#include "identify/periodic_log.hpp"
#include "identify/physical_identification.hpp"
#include "identify/pipeline.hpp"
#include "identify/plausibility.hpp"
#include "identify/report.hpp"
#include "identify/segmented_pipeline.hpp"
#include "identify/segmented_validation.hpp"
#include "identify/static_validation.hpp"
#include "identify/torque_delay.hpp"
#include "identify/validate_log.hpp"
#include "identify/validation.hpp"
#include "io/candump_joints.hpp"
#include "io/csv_table.hpp"
#include "io/distinct_inputs.hpp"
#include "io/time_axis.hpp"
#include "robot/base_parameter_report.hpp"
#include "robot/robot_description.hpp"
#if JACOBID_WITH_FIRMWARE
#include "jacobid/firmware/firmware_config_yaml.hpp"
#endif

namespace jacobid::cli {
namespace {

// FitOptions: how the log is identified (fit_options.hpp, shared with montecarlo).
struct IdentifyOptions : FitOptions {
    std::string robot;
    std::vector<std::string> inputs;  // --in, once or more
    std::string in;                   // the first --in (the one log, or the first of several)
    int threads = 0;                  // --threads: logs identified at once (0: one per core)
    std::string method = "jacobi";
    std::string format = "table";
    std::string output = "-";
    std::string report;
    std::string truth;
    std::string validate;
    std::string time_column = "t";
    bool print_base = false;
    double essential = 0.0;  // threshold in %; 0: off
    bool essential_flag = false;
    bool quiet = false;
    double time_tolerance = io::kDefaultTimeTolerance;
    std::string can_config;
    std::string velocity;               // measured | jacobi | butterworth; empty: the method's own
    LogFormatOptions log_format;
    bool physical = false;       // --physical
    bool semi_physical = false;  // --semi-physical
    double prior_weight = identify::PhysicalSettings{}.prior_weight;
    identify::ModelExportPaths model_export;  // --export-urdf, --export-robot
    DriveGainOptions drive_gains;  // --drive-gains --loaded --payload-mass ...
    std::string period;            // --period auto|SECONDS; empty: off
    std::size_t piece_rows = 0;    // --piece-rows; 0: automatic (cli/streamed_log.hpp)
};

// "a.csv", or "a.csv + b.csv" for several logs (titles, messages, the JSON's "log").
std::string log_names(const std::vector<std::string>& inputs) {
    std::string names;
    for (const std::string& in : inputs) names += (names.empty() ? "" : " + ") + in;
    return names;
}

// --period: the log averaged over its periods (periodic_log.hpp), described on stderr and in the output.
std::unique_ptr<identify::PeriodicLog> periodic_log(const LogSegments& input, const std::vector<identify::LogColumns>& logs, const IdentifyOptions& o,
                                                    const identify::IdentifySettings& settings) {
    if (o.period.empty()) return nullptr;
    if (o.inputs.size() > 1) throw InputError(fmt::format("--period with {} --in logs: periods are averaged over one continuous log", o.inputs.size()));
    if (input.split) throw InputError(fmt::format("--period with --on-gap split: {} has gaps; periods are averaged over one continuous log", o.in));
    if (identify::is_iterated(settings.estimator.estimator)) {
        throw InputError(fmt::format("--period with --estimator {}: the estimator simulates the log itself, not its mean period (use wls or ols)",
                                     identify::to_string(settings.estimator.estimator)));
    }
    auto periodic = identify::average_periods(logs.front(), identify::parse_period_option(o.period), o.pipeline.min_joint_motion);
    // The text output starts with the same line.
    if (!o.quiet && (o.format == "json" || o.output != "-")) fmt::print(stderr, "identify: {}\n", identify::describe(*periodic));
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

// The columns of a plain CSV that identify reads (identify::log_columns): time, positions and torques, the
// measured velocities qdJ with --velocity measured, the references q_refJ / qd_refJ with --estimator iv|didim.
io::CsvColumnFilter identify_columns(const io::LogColumnNames& names, const IdentifyOptions& o) {
    std::set<std::string> kept = {names.time};
    kept.insert(names.q.begin(), names.q.end());
    kept.insert(names.tau.begin(), names.tau.end());
    if (o.velocity == "measured") kept.insert(names.qd.begin(), names.qd.end());
    if (o.estimator == "iv" || o.estimator == "didim") {
        for (std::size_t j = 0; j < names.q.size(); ++j) {
            for (const std::string& column : identify::reference_column_names(j)) kept.insert(column);
        }
    }
    return [kept = std::move(kept)](const std::string& name) { return kept.count(name) != 0; };
}

// A CSV log (with --on-gap split, one table per segment), or with --can-config a candump capture decoded by
// the firmware's joint profiles.
// `period` (s, > 0): a raw log (--log-format) is resampled onto that grid instead of its own mean step.
LogSegments read_log(const std::string& path, const robot::RobotDescription& robot, const IdentifyOptions& o, double period = 0.0) {
    if (o.can_config.empty()) {
        const io::LogColumnNames names = robot_column_names(robot, o.time_column);
        return read_log_segments(path, o.log_format, names, o.quiet, period, identify_columns(names, o));
    }
    if (!o.log_format.file.empty()) throw InputError("--log-format and --can-config: give one of them");
#if JACOBID_WITH_FIRMWARE
    firmware::FirmwareConfig fw;
    try {
        fw = firmware::load_firmware_config(o.can_config);
    } catch (const firmware::ConfigError& e) {
        throw InputError(fmt::format("--can-config {}", e.what()));
    }
    if (fw.joints.size() != robot.joints.size()) {
        throw InputError(fmt::format("--can-config {}: {} joints, but the robot description has {}", o.can_config, fw.joints.size(),
                                     robot.joints.size()));
    }
    std::vector<hal::ProfileConfig> decoders;
    for (const auto& joint : fw.joints) decoders.push_back(joint.decoder);
    const io::LogColumnNames names = robot_column_names(robot, o.time_column);
    io::CandumpJointCounts counts;
    LogSegments table;
    table.tables.push_back(io::candump_joint_table(io::read_candump_log(path), decoders, names.q, names.tau, o.time_column, path, &counts));
    if (!o.quiet) {
        fmt::print(stderr, "{}: {} samples from {} decoded frames ({} frames of other ids and {} error frames skipped){}\n", path, counts.samples,
                   counts.frames_decoded, counts.frames_other_ids, counts.error_frames,
                   counts.regridded ? fmt::format("; time stamps within +-{:.3g} ms of a {:.6g} ms cycle (receive-time jitter): the nominal cycle used",
                                                  1e3 * counts.max_jitter, 1e3 * counts.cycle)
                                    : std::string());
    }
    return table;
#else
    (void)robot;
    throw InputError(fmt::format("--can-config: this jacobid was built without the HAL/firmware (JACOBID_BUILD_HAL=OFF), cannot decode {}", path));
#endif
}

std::map<std::string, double> read_truth(const std::string& path) {
    const std::string text = io::read_text_file(path, "--truth file");
    nlohmann::json j;
    try {
        j = nlohmann::json::parse(text);
    } catch (const nlohmann::json::exception& e) {
        throw InputError(fmt::format("--truth {}: invalid JSON: {}", path, e.what()));
    }
    if (!j.contains("parameters") || !j["parameters"].is_object()) throw InputError(fmt::format("--truth {}: no object 'parameters'", path));
    std::map<std::string, double> truth;
    for (auto& [name, value] : j["parameters"].items()) {
        if (!value.is_number()) throw InputError(fmt::format("--truth {}: parameter '{}' is not a number", path, name));
        truth[name] = value.get<double>();
    }
    return truth;
}

// A truth file must hold exactly the model's parameters: the truth of another robot or parameter set
// (a PUMA's for the planar 2R) was accepted, and the table showed +814 % "errors" against unrelated values.
void require_truth_of_the_model(const std::map<std::string, double>& truth, const std::vector<std::string>& names, const IdentifyOptions& o) {
    for (const std::string& name : names) {
        if (truth.count(name) == 0) {
            throw InputError(fmt::format("--truth {}: no parameter '{}', which the robot description {} has ({} parameters in the file, {} in the "
                                         "model): the truth of another robot or parameter set?",
                                         o.truth, name, o.robot, truth.size(), names.size()));
        }
    }
    for (const auto& [name, value] : truth) {
        if (std::find(names.begin(), names.end(), name) == names.end()) {
            throw InputError(fmt::format("--truth {}: parameter '{}' is not one of the robot description {}'s ({} parameters in the file, {} in the "
                                         "model): the truth of another robot or parameter set?",
                                         o.truth, io::printable_cell(name), o.robot, truth.size(), names.size()));
        }
    }
}

// The joints' columns of each table (one, or one per segment with --on-gap split).
std::vector<identify::LogColumns> columns_of(const LogSegments& logs, const robot::RobotDescription& robot, const IdentifyOptions& o) {
    std::vector<identify::LogColumns> columns;
    const double grid_period = logs.split ? logs.grid_period : 0.0;
    for (const auto& table : logs.tables) columns.push_back(identify::log_columns(table, robot, o.time_column, o.time_tolerance, grid_period));
    return columns;
}

// The segments' report lines, each segment not used also on stderr (never dropped silently).
std::vector<identify::SegmentReport> segment_reports(const std::vector<io::LogSegment>& segments, const std::vector<bool>& used,
                                                     const std::vector<std::string>& why, const char* method, const std::string& path) {
    std::vector<identify::SegmentReport> reports;
    for (std::size_t s = 0; s < segments.size(); ++s) {
        const io::LogSegment& g = segments[s];
        reports.push_back({g.first_line, g.last_line, g.duration, g.samples, used[s], why[s], 0, ""});
        if (!used[s]) fmt::print(stderr, "jacobid identify [{}]: {}: segment {} ({}) not used: {}\n", method, path, s + 1, g.describe(), why[s]);
    }
    return reports;
}

// The logs of --in, read on up to o.threads threads (in --in order whatever the threads), and their
// columns: one per log, or one per segment with --on-gap split; `pieces` says where each comes from.
struct InputLogs {
    std::vector<LogSegments> read;                  // per --in
    std::vector<identify::LogColumns> columns;      // every log's, or every segment's, in --in order
    std::vector<identify::SegmentReport> pieces;    // per entry of `columns`: log path (several logs), lines, duration, samples
    std::vector<std::string> names;                 // per entry of `columns`, for messages: "a.csv", "a.csv: segment 2 (lines ...)"
    std::unique_ptr<StreamedLog> streamed;          // one CSV log read piece by piece: `columns` holds its first piece
    bool several() const { return read.size() > 1; }
    bool split() const { return !read.empty() && read.front().split; }
    bool in_pieces() const { return streamed && streamed->several(); }
};

// One plain CSV log that a least-squares estimator identifies: read piece by piece when it is longer than a
// piece (cli/streamed_log.hpp). The estimators that simulate the log (iv, didim) and --period need it whole.
bool streamable(const IdentifyOptions& o) {
    const LogFormatOptions& f = o.log_format;
    return o.inputs.size() == 1 && f.file.empty() && !f.read.skip_bad_rows && f.on_gap == "error" && !(f.read.max_gap > 0.0) &&
           o.can_config.empty() && o.period.empty() && o.estimator != "iv" && o.estimator != "didim";
}

InputLogs read_inputs(const robot::RobotDescription& robot, const IdentifyOptions& o) {
    io::require_distinct_inputs("--in", o.inputs);  // one log twice (a link, a copy) would count its equations twice
    InputLogs in;
    in.read.resize(o.inputs.size());
    if (streamable(o)) {
        const io::LogColumnNames names = robot_column_names(robot, o.time_column);
        in.streamed = std::make_unique<StreamedLog>(
            robot, StreamedLogSettings{o.in, identify_columns(names, o), o.time_column, o.time_tolerance, o.piece_rows, !o.quiet});
        in.read[0].tables.push_back(std::move(in.streamed->first()));
    } else if (o.piece_rows > 0) {
        throw InputError("--piece-rows: only a plain CSV log (one --in, without --log-format or --can-config) identified by least squares "
                         "(not --estimator iv|didim or --period) is read in pieces");
    }
    ParallelForOptions pool;
    pool.threads = o.threads;
    // Raw logs (--log-format) are resampled onto one grid, the first log's, so that one plan serves them all
    // (each on its own mean step, the UR10e's Fourier runs differ by up to 2 % and were refused).
    const bool one_grid = !o.log_format.file.empty() && o.inputs.size() > 1;
    if (one_grid) in.read[0] = read_log(o.inputs[0], robot, o);
    const double period = one_grid ? in.read[0].grid_period : 0.0;
    const std::vector<std::exception_ptr> errors = parallel_for(o.inputs.size(), pool, [&](std::size_t k) {
        if (!(one_grid && k == 0) && !in.streamed) in.read[k] = read_log(o.inputs[k], robot, o, period);
    });
    for (const auto& e : errors) {
        if (e) std::rethrow_exception(e);  // the first --in that failed, whatever the threads
    }
    for (std::size_t k = 0; k < in.read.size(); ++k) {
        const LogSegments& logs = in.read[k];
        std::vector<identify::LogColumns> columns = columns_of(logs, robot, o);
        // The time stamps have given each piece its period and start: nothing reads them again.
        for (io::CsvTable& table : in.read[k].tables) table.release(o.time_column);
        for (std::size_t s = 0; s < columns.size(); ++s) {
            identify::SegmentReport piece;
            if (in.several()) piece.log = o.inputs[k];
            piece.samples = columns[s].samples();
            piece.duration = piece.samples > 1 ? static_cast<double>(piece.samples - 1) * columns[s].sample_period : 0.0;
            std::string name = o.inputs[k];
            if (in.in_pieces()) {
                const io::CsvTable& table = logs.tables[s];
                piece.first_line = table.line_of_row(0);
                piece.last_line = table.line_of_row(table.rows() - 1);
                piece.log = o.inputs[k];  // each piece on its own line of the report, with its equations
                name = StreamedLog::piece_name(o.inputs[k], 1, piece.first_line, piece.last_line);
            }
            if (s < logs.segments.size() && logs.split) {
                piece.first_line = logs.segments[s].first_line;
                piece.last_line = logs.segments[s].last_line;
                piece.duration = logs.segments[s].duration;
                name += fmt::format(": segment {} ({})", s + 1, logs.segments[s].describe());
            }
            // One plan (windows, F_p, decimation in samples) serves every piece: the logs must share their sampling.
            if (!in.columns.empty()) {
                const double first_period = in.columns.front().sample_period;
                if (std::abs(columns[s].sample_period - first_period) > 1e-3 * first_period) {
                    throw InputError(fmt::format("--in {}: sampled every {:.6g} ms, but --in {} every {:.6g} ms; logs identified together must share "
                                                 "their sample period (resample one of them)",
                                                 o.inputs[k], 1e3 * columns[s].sample_period, o.inputs.front(), 1e3 * first_period));
                }
            }
            // A given --cutoff is refused above the Nyquist frequency (as differentiate does), not clamped to
            // the shortest windows: the settings line would name another cutoff than the one asked for.
            const double nyquist = 0.5 / columns[s].sample_period;
            if (o.pipeline.differentiator_cutoff >= nyquist) {
                throw InputError(fmt::format("--cutoff {:g} Hz: must be below the Nyquist frequency {:g} Hz of --in {} (sample period {:g} s)",
                                             o.pipeline.differentiator_cutoff, nyquist, o.inputs[k], columns[s].sample_period));
            }
            in.pieces.push_back(piece);
            in.names.push_back(name);
            in.columns.push_back(std::move(columns[s]));
        }
    }
    return in;
}

// The report lines of the pieces (segments and/or logs); each piece not used also on stderr (never dropped silently).
// A log read piece by piece: its first piece freed once identified, so that one piece at a time is held, and
// read again for the next method.
void release_first_piece(InputLogs& in) {
    in.columns.front() = identify::LogColumns{};
    std::vector<io::CsvTable>().swap(in.read.front().tables);
}

void read_first_piece_again(InputLogs& in, const robot::RobotDescription& robot, const IdentifyOptions& o) {
    std::vector<io::CsvTable>& tables = in.read.front().tables;
    tables.push_back(in.streamed->read_first_again());
    in.columns.front() = identify::log_columns(tables.front(), robot, o.time_column, o.time_tolerance, 0.0);
    tables.front().release(o.time_column);
}

// `reports` and `names`: those of the pieces read in advance (InputLogs), then of those read piece by piece.
std::vector<identify::SegmentReport> piece_reports(std::vector<identify::SegmentReport> reports, const std::vector<std::string>& names,
                                                   const identify::SegmentedOutput& split, const char* method) {
    for (std::size_t s = 0; s < reports.size(); ++s) {
        identify::SegmentReport& r = reports[s];
        r.used = split.used[s];
        r.why = split.why[s];
        r.rows = split.rows[s];
        if (!r.used) fmt::print(stderr, "jacobid identify [{}]: {} not used: {}\n", method, names[s], r.why);
    }
    return reports;
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

void run(IdentifyOptions o) {
    map_large_blocks();  // whole-log buffers returned when freed (core/free_memory.hpp)
    const robot::RobotDescription robot = robot::load_robot_description(o.robot);
    std::vector<NamedPath> read_files = robot_files("--robot", o.robot, robot);
    read_files.insert(read_files.end(), {{"--truth", o.truth}, {"--validate", o.validate}, {"--can-config", o.can_config},
                                         {"--log-format", o.log_format.file}, {"--loaded", o.drive_gains.loaded}});
    for (const std::string& in : o.inputs) read_files.push_back({"--in", in});
    check_outputs({{"--output", o.output}, {"--export-urdf", o.model_export.urdf}, {"--export-robot", o.model_export.robot}}, read_files);
    using Clock = std::chrono::steady_clock;
    const auto model = robot::make_robot_model(robot);
    if (o.print_base) {
        // The model alone: base parameters, regrouping relations and true values; no log needed.
        write_output(o.output, o.format == "json" ? robot::base_parameter_json(robot, *model).dump(2) + "\n" : robot::base_parameter_text(robot, *model));
        return;
    }
    if (o.in.empty()) throw InputError("--in is required (a log to identify from), unless --print-base");
    if (o.threads < 0) throw InputError(fmt::format("--threads {}: must be >= 0 (0: one per core)", o.threads));
    if (o.threads == 0) o.threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    o.pipeline.threads = o.threads;  // one log: its regressor, F_p and QR on every thread (several: see run_segmented_pipeline)
    // The decimated rows kept for the fit plots only serve --report (20 000 rows of 6 x 53 columns: 51 MB).
    if (o.report.empty()) o.pipeline.plot_rows = 0;
    if (o.drive_gains.enabled) {
        if (o.inputs.size() > 1) {
            throw InputError(fmt::format("--drive-gains with {} --in logs: give the unloaded run as --in and the loaded one as --loaded", o.inputs.size()));
        }
        const std::vector<std::pair<std::string, bool>> given = {{"--validate", !o.validate.empty()}, {"--report", !o.report.empty()},
                                                                 {"--truth", !o.truth.empty()},       {"--essential", o.essential_flag},
                                                                 {"--physical", o.physical || o.semi_physical}, {"--can-config", !o.can_config.empty()},
                                                                 {"--velocity", !o.velocity.empty()},
                                                                 {"--export-urdf / --export-robot", o.model_export.any()},
                                                                 {"--period", !o.period.empty()}};
        write_output(o.output, run_drive_gains(robot, *model, o.drive_gains, o, o.method,
                                               {o.in, o.format, o.time_column, o.time_tolerance, o.quiet, &o.log_format, given}));
        return;
    }
    read_files.push_back({"--output", o.output});
    check_output_directory({"--report", o.report}, read_files);  // written after the work: checked before it
    const std::map<std::string, double> truth = o.truth.empty() ? std::map<std::string, double>{} : read_truth(o.truth);
    if (!o.truth.empty()) require_truth_of_the_model(truth, model->parameter_names(), o);
    // Refused before the (long) identification; exporting needs standard parameters: --physical unless --semi-physical.
    identify::check_model_export(o.model_export, robot);
    o.physical = o.physical || (o.model_export.any() && !o.semi_physical);
    const std::optional<identify::PhysicalSettings> physical = physical_settings(o);
    const auto parse_start = Clock::now();
    InputLogs inputs = read_inputs(robot, o);
    const LogSegments& input = inputs.read.front();
    const std::vector<identify::LogColumns>& logs = inputs.columns;
    // Several pieces (segments of a log cut at its gaps, several logs, or both) are identified together.
    const bool pieces = inputs.split() || inputs.several() || inputs.in_pieces();
    const std::unique_ptr<identify::PeriodicLog> periodic = periodic_log(input, logs, o, identify_settings(o, identify::Method::Jacobi));
    const identify::LogColumns& log = periodic ? periodic->columns : logs.front();
    const double parse_seconds = std::chrono::duration<double>(Clock::now() - parse_start).count();
    std::size_t samples = 0;
    for (const auto& l : logs) samples += l.samples();
    if (inputs.in_pieces()) samples = inputs.streamed->estimated_rows();
    o.pipeline.progress = !o.quiet && samples > 500'000;
    if (o.pipeline.progress) {
        fmt::print(stderr, "identify: read {} rows of {} in {:.2f} s{}\n", logs.front().samples(), log_names(o.inputs), parse_seconds,
                   inputs.in_pieces() ? fmt::format(" (its first piece: about {} rows in all, read piece by piece)", samples) : std::string());
    }

    LogSegments validation_input;
    std::vector<identify::LogColumns> validation_logs;
    if (!o.validate.empty()) {
        validation_input = read_log(o.validate, robot, o);
        validation_logs = columns_of(validation_input, robot, o);
    }

    identify::ReportContext ctx;
    ctx.log_source = log_names(o.inputs);
    ctx.model_name = model->model_name();
    for (const auto& j : robot.joints) ctx.joint_names.push_back(j.name);
    ctx.truth = truth;
    if (periodic) ctx.warnings.insert(ctx.warnings.end(), periodic->warnings.begin(), periodic->warnings.end());
    for (const std::string& in : o.validate.empty() ? std::vector<std::string>{} : o.inputs) {  // a validation that validates nothing
        const std::string why = io::same_log(in, o.validate);
        if (!why.empty()) ctx.warnings.push_back(fmt::format("--validate {} is the --in log ({}): its validation figures are in-sample", o.validate, why));
    }

    std::vector<identify::MethodResult> results;
    for (const identify::Method m : methods_of(o.method)) {
        identify::PipelineSettings settings = method_pipeline(o.pipeline, m, o.velocity, o.method);
        const identify::IdentifySettings resolved = identify_settings(o, m);
        identify::SolveOptions solve = resolved.solve;
        if (periodic) {
            settings = identify::periodic_settings(settings, *periodic);
            solve.joint_noise = periodic->torque_noise;
        }
        if (identify::is_iterated(resolved.estimator.estimator) && pieces) {
            throw InputError(inputs.several() ? fmt::format("--estimator {} with {} --in logs: the estimator simulates one continuous log",
                                                            identify::to_string(resolved.estimator.estimator), o.inputs.size())
                                              : fmt::format("--estimator {}: {} is split at its gaps (--on-gap split); the estimator simulates one continuous log",
                                                            identify::to_string(resolved.estimator.estimator), o.in));
        }
        if (identify::is_iterated(resolved.estimator.estimator) && physical) {
            throw InputError(fmt::format("--{} with --estimator {}: the physically consistent fit is a least-squares one (use wls or ols)",
                                         identify::to_string(physical->constraint), identify::to_string(resolved.estimator.estimator)));
        }
        if (resolved.estimator.estimator == identify::Estimator::Iv && o.essential_flag) {
            throw InputError("--essential with --estimator iv: the essential parameters are chosen by least squares (use wls or didim)");
        }
        identify::IdentifiedLog fit;
        std::optional<identify::ShiftedTorques> first_aligned;  // what the first piece's torques are read from
        if (pieces) {
            // Every segment or log with the choices resolved on the longest one, the equations stacked (segmented_pipeline.hpp):
            // the delay with the description's alpha, then each joint's alpha (friction alpha: auto) on the aligned log.
            identify::SegmentSource source;
            if (inputs.several()) source = {"--in", "log"};
            if (inputs.in_pieces()) source = {"--piece-rows", "piece"};
            if (inputs.in_pieces() && logs.front().q.empty()) read_first_piece_again(inputs, robot, o);  // freed by the method before
            const identify::SegmentPlan plan = identify::plan_segments(logs, settings, source);
            identify::TorqueDelayResult delay = identify::resolve_torque_delay(*model, logs[plan.reference], plan.fixed, solve, given_torque_delay(o));
            if (inputs.in_pieces()) {
                // A log read piece by piece: its first piece is read again for a further method, so its torques,
                // read by nothing else now, are aligned in place (every later piece's are, by the pipeline),
                // not into a copy beside the piece (173 MB for an hour of 6-axis torques).
                identify::LogColumns& first = inputs.columns.front();
                first.own_tau = identify::writable_torques(inputs.read.front().tables.front(), first);
                first_aligned = identify::shift_torques(first, delay.applied());  // holds no copy: in place
                first = first_aligned->log;
            }
            identify::SmoothedModel smoothed = [&] {
                const identify::ShiftedTorques reference = identify::shift_torques(logs[plan.reference], delay.applied());
                return identify::resolve_coulomb_smoothing(robot, *model, reference.log, plan.fixed, solve.weighted);
            }();  // an aligned copy of the reference's torques is not held through the identification
            std::vector<identify::SegmentReport> piece_lines = inputs.pieces;
            std::vector<std::string> piece_names = inputs.names;
            const identify::NextSegment more =
                inputs.in_pieces() ? inputs.streamed->rest(logs.front().sample_period, piece_lines, piece_names, [&] { release_first_piece(inputs); })
                                   : nullptr;
            identify::SegmentedOutput split = identify::run_segmented_pipeline(smoothed.get(*model), logs, plan, delay.applied(), o.threads, more);
            std::vector<identify::SegmentReport> reports = piece_reports(std::move(piece_lines), piece_names, split, identify::to_string(m));
            fit = identify::solve_identification(std::move(split.merged), std::move(smoothed), std::move(delay), *model, solve);
            fit.result.segments = std::move(reports);
        } else {
            // One method reads the log's torques once: they are aligned in place rather than copied.
            identify::LogColumns view = log;
            if (!periodic && methods_of(o.method).size() == 1) view.own_tau = identify::writable_torques(inputs.read.front().tables.front(), view);
            fit = identify::identify_log(robot, *model, view, {settings, solve, given_torque_delay(o), resolved.estimator});
        }
        if (physical) identify::make_physically_consistent(fit, robot, *model, *physical);
        const robot::RobotModel& fitted = fit.smoothed.get(*model);
        identify::MethodResult& r = fit.result;
        if (o.essential_flag) r.essential = identify::essential_parameters(fit.factors, fitted.parameter_names(), o.essential, solve);
        if (!o.validate.empty()) validate(fitted, validation_input, validation_logs, settings, o, r);
        for (const auto& w : identify::identifiability_warnings(r, ctx.joint_names)) {
            ctx.warnings.push_back(fmt::format("[{}] {}", identify::to_string(m), w));
        }
        results.push_back(std::move(r));
    }
    for (const auto& w : ctx.warnings) fmt::print(stderr, "jacobid identify: warning: {}\n", w);
    for (const auto& r : results) identify::require_finite_solution(r.solution, o.in);

    std::optional<nlohmann::json> exported;
    if (o.model_export.any()) exported = write_model_export(o.model_export, robot, results.front(), o.in);
    std::string text;
    if (o.format == "json") {
        nlohmann::json j;
        // One layout whatever --method: every method under "methods" (what scripts should read), and the first
        // method's fields also at the top level, as single-method output always had them.
        j = identify::to_json(results.front(), ctx);
        for (const auto& r : results) j["methods"][identify::to_string(r.info.method)] = identify::to_json(r, ctx);
        j["log"] = log_names(o.inputs);
        j["logs"] = o.inputs;
        j["model"] = model->model_name();
        j["parse_seconds"] = parse_seconds;
        if (exported) j["export"] = *exported;
        if (periodic) j["period"] = identify::to_json(*periodic);
        text = j.dump(2) + "\n";
    } else {
        text = (periodic ? identify::describe(*periodic) + "\n\n" : "") + identify::format_table(results, ctx) +
               (exported ? identify::describe_export(*exported) : "");
    }
    write_output(o.output, text);
    if (!o.report.empty()) identify::write_report(o.report, results, ctx);
}

}  // namespace

void add_identify_command(CLI::App& app) {
    auto o = std::make_shared<IdentifyOptions>();
    CLI::App* cmd = app.add_subcommand("identify",
                                       "identify base dynamic parameters from a log (t, positions, torques) by least squares on the "
                                       "decimated inverse dynamic model; prints the paper's Table II");
    cmd->add_option("--robot", o->robot, "robot description (YAML, e.g. 'model: planar2r')")->required()->check(file_path());
    cmd->add_option("--in", o->inputs,
                    "log (CSV with a header: time column, the joints' position and torque columns); repeat it (--in a.csv --in b.csv) to "
                    "identify several logs together: each log keeps its own edges, their equations are stacked")
        ->expected(1)
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)->check(file_path());
    cmd->add_option("--piece-rows", o->piece_rows,
                    "rows of a long CSV log held at once (default 0: as many as fit in 400 MB of its kept columns, an hour of 1 kHz "
                    "6-axis data): a longer log is identified piece by piece, like the segments of --on-gap split, so memory does "
                    "not grow with the log")
        ->check(whole_number_from(0))
        ->capture_default_str();
    cmd->add_option("--threads", o->threads,
                    "threads (0: one per core): several logs (or --on-gap split segments) are processed at once, one log's regressor, "
                    "F_p and least squares are split over them; the results do not depend on it")
        ->capture_default_str();
    cmd->add_flag("--print-base", o->print_base,
                  "print the robot's base parameters with their regrouping relations (e.g. ZZ1R = ZZ1 + IA1 + 0.25*M2) and true values, "
                  "then exit (no --in needed)");
    cmd->add_option("--method", o->method, "jacobi, butterworth, or both side by side")
        ->check(CLI::IsMember({"jacobi", "butterworth", "both"}))
        ->capture_default_str();
    cmd->add_option("--format", o->format, "table (Table II text) or json")->check(CLI::IsMember({"table", "json"}))->capture_default_str();
    cmd->add_option("--output,-o", o->output, "output file, '-' for standard output")->capture_default_str()->check(file_path(true));
    cmd->add_option("--report", o->report, "also write DIR/report.md and PNG plots (torque measured vs model)")->check(file_path());
    cmd->add_option("--truth", o->truth, "truth JSON (from jacobid simulate): adds the true values and errors to the table")->check(file_path());
    cmd->add_option("--validate", o->validate, "second log: predict its torques with the identified parameters, report RMS errors; a log that holds a pose gets the static (gravity) check per joint")->check(file_path());
    cmd->add_option("--time-column", o->time_column, "name of the time column (s)")->capture_default_str();
    add_time_tolerance_option(cmd, o->time_tolerance);
    cmd->add_option("--can-config", o->can_config,
                    "jacobid-fw config (YAML) whose joints' CAN profiles, ids, gear ratios and torque constants decode --in and "
                    "--validate as candump -L captures instead of CSV")->check(file_path());
    add_log_format_options(cmd, o->log_format);
    add_fit_options(cmd, *o);
    cmd->add_option("--velocity", o->velocity,
                    "velocities of the regressor: measured (the log's velocity columns, qdJ or --log-format velocities), or jacobi / "
                    "butterworth (the positions differentiated; default: the --method's own differentiator)")
        ->check(CLI::IsMember({"measured", "jacobi", "butterworth"}));
    cmd->add_option("--essential", o->essential,
                    "essential parameters: drop the parameter with the largest %sigma_r above this threshold (%), re-identify, repeat")
        ->check(positive_number())
        ->each([o](const std::string&) { o->essential_flag = true; })
        ->expected(0, 1)
        ->default_str("10");
    cmd->add_flag("--physical", o->physical,
                  "physically consistent parameters: every link's pseudo-inertia positive definite (positive mass, positive definite "
                  "inertia, triangle inequalities), rotor inertias and friction coefficients >= 0; the standard parameters nearest the "
                  "description's (URDF) values among those that fit the data, reported with the active constraints (mdh/urdf models)");
    cmd->add_flag("--semi-physical", o->semi_physical,
                  "as --physical without the triangle inequalities: positive mass and positive definite inertia about the centre of mass");
    cmd->add_option("--prior-weight", o->prior_weight,
                    "weight of the description's standard values in --physical: w sum ((s - prior) / unit)^2 beside the data's chi^2 "
                    "(units 0.01 kg.m^2, 0.1 kg.m, 1 kg, 1 N.m); it decides only what the log does not excite")
        ->check(non_negative_number())
        ->capture_default_str();
    add_model_export_options(cmd, o->model_export);
    add_drive_gain_options(cmd, o->drive_gains);
    cmd->add_option("--period", o->period,
                    "the log repeats one trajectory with this period (s, a whole number of samples), or 'auto' to detect it from the "
                    "positions: the whole periods are averaged (noise / sqrt(periods)), the period-to-period spread gives each joint's "
                    "noise for the weights, and the mean period is identified as a periodic signal (no edges lost)");
    cmd->add_flag("--quiet", o->quiet, "no progress messages on stderr");
    cmd->callback([o] {
        o->in = o->inputs.empty() ? std::string() : o->inputs.front();
        if (o->essential_flag && o->essential <= 0.0) o->essential = 10.0;
        o->pipeline.exact_discretization = o->discretization == "exact";
        run(*o);
    });
}

}  // namespace jacobid::cli
