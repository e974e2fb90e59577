// SPDX-License-Identifier: MIT
// jacobid diagnose: where the identified model and the measured data disagree, which physical effect is
// missing, and how much the gap shrinks on held-out data once it is added (docs/diagnose.md).
#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include <cmath>
#include <memory>

#include "cli/command.hpp"
#include "cli/fit_options.hpp"
#include "cli/option_checks.hpp"
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

// The search's sizes that follow from the options and the log, refused before the search allocates them.
// The bounds are far above any real use: 1000 folds (5 is the default), a delay grid of 20001 one-sample
// shifts (+-10 s at 1 kHz), 100000 cogging candidates (30 orders per joint is the default).
void refuse_oversized_search(const DiagnoseOptions& o, const identify::LogColumns& log, const robot::RobotModel& model) {
    const auto& s = o.settings.selection;
    const double joints = model.joint_count(), columns = model.parameter_count(), samples = static_cast<double>(log.samples());
    // Each fold keeps one Gram matrix per joint.
    refuse_oversized(fmt::format("--folds {}", s.folds), s.folds, 1000, "folds", joints * columns * columns * 8.0, "lower --folds");
    // Each delay candidate re-solves the selection with the torques shifted by one more sample (a cost in time).
    refuse_oversized(fmt::format("--max-delay {:g} s at the log's sample period {:g} s", s.max_delay, log.sample_period),
                     2.0 * std::round(s.max_delay / log.sample_period) + 1.0, 20001, "delay candidates", 0.0, "lower --max-delay");
    // Each cogging order adds a sine and a cosine column over the whole log, per joint.
    refuse_oversized(fmt::format("--max-cogging-order {}", o.settings.catalogue.max_cogging_order),
                     joints * (o.settings.catalogue.max_cogging_order - 1), 1e5, "cogging candidates", 2.0 * samples * 8.0,
                     "lower --max-cogging-order");
}

void run(DiagnoseOptions o) {
    check_outputs({{"--output", o.output}}, {{"--robot", o.robot}, {"--in", o.in}, {"--validate", o.validate}, {"--log-format", o.log_format.file}});
    // Its blocked cross-validation and horizon simulations read one continuous record (docs/log-format.md).
    refuse_split(o.log_format, "diagnose");
    const robot::RobotDescription robot = robot::load_robot_description(o.robot);
    const auto model = robot::make_robot_model(robot);
    const io::CsvTable table = read_log_table(o.in, o.log_format, robot_column_names(robot, o.time_column), o.quiet);
    const identify::LogColumns log = identify::log_columns(table, robot, o.time_column, o.time_tolerance);
    refuse_oversized_search(o, log, *model);
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
    add_time_tolerance_option(cmd, o->time_tolerance);
    add_log_format_options(cmd, o->log_format);
    cmd->add_option("--alpha", o->settings.selection.alpha, "significance level of each step (Bonferroni over all candidates tried)")
        ->check(number_between(0.0, 1.0))
        ->capture_default_str();
    cmd->add_option("--min-gain", o->settings.selection.min_gain, "minimum relative reduction of the held-out error for a candidate to be named")
        ->check(number_in(0.0, 1.0))
        ->capture_default_str();
    cmd->add_option("--max-effects", o->settings.selection.max_effects, "stop after naming this many effects")
        ->check(whole_number_from(0))
        ->capture_default_str();
    cmd->add_option("--folds", o->settings.selection.folds, "blocks of the blocked cross-validation (without --validate)")
        ->check(whole_number_from(2))
        ->capture_default_str();
    cmd->add_option("--max-delay", o->settings.selection.max_delay, "torque delays searched in [-max, max] s")->check(positive_number())->capture_default_str();
    cmd->add_flag("--no-delay", o->no_delay, "do not search a torque delay");
    cmd->add_option("--max-cogging-order", o->settings.catalogue.max_cogging_order, "cogging harmonics tried: 2..this order per revolution")
        ->check(whole_number_from(1))
        ->capture_default_str();
    cmd->add_option("--horizon", o->settings.horizon.horizon, "length of the short-horizon simulations in s")->check(positive_number())->capture_default_str();
    cmd->add_option("--horizon-spacing", o->settings.horizon.spacing, "time between the starts of the short-horizon simulations in s")
        ->check(positive_number())
        ->capture_default_str();
    add_pipeline_rate_options(cmd, o->settings.pipeline);
    cmd->add_flag("--quiet", o->quiet, "no progress messages on stderr");
    cmd->callback([o] { run(*o); });
}

}  // namespace jacobid::cli
