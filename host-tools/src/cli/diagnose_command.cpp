// SPDX-License-Identifier: MIT
// jacobid diagnose: where the identified model and the measured data disagree, which physical effect is
// missing, and how much the gap shrinks on held-out data once it is added (docs/diagnose.md).
#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include <memory>

#include "cli/command.hpp"
#include "cli/log_format_options.hpp"
#include "identify/coulomb_smoothing.hpp"
#include "identify/log_columns.hpp"
#include "cli/output_file.hpp"
#include "diagnose/diagnosis.hpp"
#include "diagnose/diagnosis_report.hpp"
#include "io/csv_table.hpp"
#include "io/time_axis.hpp"
#include "robot/robot_description.hpp"

namespace jacobid::cli {
namespace {

struct DiagnoseOptions {
    std::string robot, in, validate, report;
    std::string format = "table";
    std::string output = "-";
    std::string time_column = "t";
    double time_tolerance = io::kDefaultTimeTolerance;
    diagnose::DiagnoseSettings settings;
    bool no_delay = false;
    bool quiet = false;
    LogFormatOptions log_format;
};

void check(const DiagnoseOptions& o) {
    const auto& s = o.settings.selection;
    if (!(s.alpha > 0.0 && s.alpha < 1.0)) throw InputError("--alpha must be in (0, 1)");
    if (!(s.min_gain >= 0.0 && s.min_gain < 1.0)) throw InputError("--min-gain must be in [0, 1)");
    if (s.max_effects < 0) throw InputError("--max-effects must be >= 0");
    if (s.folds < 2) throw InputError("--folds must be >= 2");
    if (!(s.max_delay > 0.0)) throw InputError("--max-delay must be > 0 s");
    if (o.settings.catalogue.max_cogging_order < 1) throw InputError("--max-cogging-order must be >= 1");
    if (!(o.settings.horizon.horizon > 0.0) || !(o.settings.horizon.spacing > 0.0)) throw InputError("--horizon and --horizon-spacing must be > 0 s");
}

void run(DiagnoseOptions o) {
    check_outputs({{"--output", o.output}}, {{"--robot", o.robot}, {"--in", o.in}, {"--validate", o.validate}, {"--log-format", o.log_format.file}});
    check(o);
    // Its blocked cross-validation and horizon simulations read one continuous record (docs/log-format.md).
    refuse_split(o.log_format, "diagnose");
    const robot::RobotDescription robot = robot::load_robot_description(o.robot);
    const auto model = robot::make_robot_model(robot);
    const io::CsvTable table = read_log_table(o.in, o.log_format, robot_column_names(robot, o.time_column), o.quiet);
    const identify::LogColumns log = identify::log_columns(table, robot, o.time_column, o.time_tolerance);
    std::unique_ptr<io::CsvTable> vtable;
    identify::LogColumns vlog;
    if (!o.validate.empty()) {
        vtable = std::make_unique<io::CsvTable>(read_log_table(o.validate, o.log_format, robot_column_names(robot, o.time_column), o.quiet, log.sample_period));
        vlog = identify::log_columns(*vtable, robot, o.time_column, o.time_tolerance);
        if (std::abs(vlog.sample_period - log.sample_period) > 1e-9 * log.sample_period) {
            throw InputError(fmt::format("--validate {}: sample period {} s differs from {} s of --in", o.validate, vlog.sample_period, log.sample_period));
        }
    }
    o.settings.selection.search_delay = !o.no_delay;
    o.settings.catalogue.torque_delay = !o.no_delay;
    auto progress = [&](const std::string& line) {
        if (!o.quiet) fmt::print(stderr, "diagnose: {}\n", line);
    };
    // friction alpha: auto is chosen on the identification log, as identify does, before the search.
    const identify::SmoothedModel smoothed = identify::resolve_coulomb_smoothing(robot, *model, log, o.settings.pipeline, false);
    robot::RobotDescription fitted = robot;
    std::vector<std::string> names;
    for (const auto& j : robot.joints) names.push_back(j.name);
    if (smoothed.choice) fitted.coulomb_alpha = smoothed.choice->alphas();
    const sim::EffectContext context{model->model_name(), model->joint_count(), fitted.coulomb, robot::joint_coulomb_signs(fitted)};
    diagnose::Diagnosis d = diagnose::run_diagnosis(smoothed.get(*model), context, log, o.validate.empty() ? nullptr : &vlog, o.settings, progress);
    d.joint_names = names;
    if (smoothed.choice) d.notes.push_back(identify::describe(*smoothed.choice, names));
    write_output(o.output, o.format == "json" ? diagnose::to_json(d).dump(2) + "\n" : diagnose::format_text(d));
    if (!o.report.empty()) {
        diagnose::write_report(o.report, d);
        progress(fmt::format("report written to {}/report.md", o.report));
    }
}

}  // namespace

void add_diagnose_command(CLI::App& app) {
    auto o = std::make_shared<DiagnoseOptions>();
    CLI::App* cmd = app.add_subcommand(
        "diagnose",
        "find where the identified model and the measured data disagree, name the missing physical effect (coulomb_offset, "
        "coulomb_asymmetry, stribeck, viscous_nonlinear, gravity, cogging, rotor_inertia, torque_delay), add it and show the gap "
        "shrink on held-out data");
    cmd->add_option("--robot", o->robot, "robot description (YAML, as for identify)")->required();
    cmd->add_option("--in", o->in, "log (CSV: time column, the joints' position and torque columns)")->required();
    cmd->add_option("--validate", o->validate, "held-out log for the selection and the before/after figures (default: blocked cross-validation)");
    cmd->add_option("--format", o->format, "table (text) or json")->check(CLI::IsMember({"table", "json"}))->capture_default_str();
    cmd->add_option("--output,-o", o->output, "output file, '-' for standard output")->capture_default_str();
    cmd->add_option("--report", o->report, "also write DIR/report.md with PNG plots of the residual vs velocity and position, before and after");
    cmd->add_option("--time-column", o->time_column, "name of the time column (s)")->capture_default_str();
    cmd->add_option("--time-tolerance", o->time_tolerance, "allowed deviation of each time step from the sample period, as a fraction")
        ->capture_default_str();
    add_log_format_options(cmd, o->log_format);
    cmd->add_option("--alpha", o->settings.selection.alpha, "significance level of each step (Bonferroni over all candidates tried)")
        ->capture_default_str();
    cmd->add_option("--min-gain", o->settings.selection.min_gain, "minimum relative reduction of the held-out error for a candidate to be named")
        ->capture_default_str();
    cmd->add_option("--max-effects", o->settings.selection.max_effects, "stop after naming this many effects")->capture_default_str();
    cmd->add_option("--folds", o->settings.selection.folds, "blocks of the blocked cross-validation (without --validate)")->capture_default_str();
    cmd->add_option("--max-delay", o->settings.selection.max_delay, "torque delays searched in [-max, max] s")->capture_default_str();
    cmd->add_flag("--no-delay", o->no_delay, "do not search a torque delay");
    cmd->add_option("--max-cogging-order", o->settings.catalogue.max_cogging_order, "cogging harmonics tried: 2..this order per revolution")
        ->capture_default_str();
    cmd->add_option("--horizon", o->settings.horizon.horizon, "length of the short-horizon simulations in s")->capture_default_str();
    cmd->add_option("--horizon-spacing", o->settings.horizon.spacing, "time between the starts of the short-horizon simulations in s")
        ->capture_default_str();
    cmd->add_option("--bandwidth", o->settings.pipeline.bandwidth, "motion bandwidth in Hz (default: estimated, as identify)");
    cmd->add_option("--cutoff", o->settings.pipeline.differentiator_cutoff, "differentiator cutoff in Hz (default: 10 x bandwidth)");
    cmd->add_option("--decimation-cutoff", o->settings.pipeline.decimation_cutoff, "cutoff of the decimation filter F_p in Hz (default: 5 x bandwidth)");
    cmd->add_option("--decimation", o->settings.pipeline.decimation, "decimation factor (default: fs / (4 x F_p cutoff))");
    cmd->add_flag("--quiet", o->quiet, "no progress messages on stderr");
    cmd->callback([o] { run(*o); });
}

}  // namespace jacobid::cli
