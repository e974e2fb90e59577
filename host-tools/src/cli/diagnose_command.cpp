// SPDX-License-Identifier: MIT
// jacobid diagnose: where the identified model and the measured data disagree, which physical effect is
// missing, and how much the gap shrinks on held-out data once it is added (docs/diagnose.md).
#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include <cmath>
#include <memory>
#include <vector>

#include "core/free_memory.hpp"
#include "cli/command.hpp"
#include "options/diagnose_options.hpp"
#include "options/fit_options.hpp"
#include "options/option_checks.hpp"
#include "options/log_format_options.hpp"
#include "identify/friction/coulomb_smoothing.hpp"
#include "identify/plan/log_columns.hpp"
#include "options/output_file.hpp"
#include "options/robot_files.hpp"
#include "diagnose/diagnose_log.hpp"
#include "diagnose/diagnosis.hpp"
#include "diagnose/diagnosis_report.hpp"
#include "io/csv_table.hpp"
#include "io/distinct_inputs.hpp"
#include "io/time_axis.hpp"
#include "robot/robot_description.hpp"

namespace jacobid::cli {
namespace {

struct DiagnoseOptions {
    std::string robot, validate, report;
    std::vector<std::string> inputs;  // --in, once per log
    std::string format = "table";
    std::string output = "-";
    std::string time_column = "t";
    double time_tolerance = io::kDefaultTimeTolerance;
    diagnose::DiagnoseSettings settings;
    bool no_delay = false;
    bool quiet = false;
    LogFormatOptions log_format;
};

void run(DiagnoseOptions o) {
    map_large_blocks();  // whole-log buffers returned when freed (core/free_memory.hpp)
    const robot::RobotDescription robot = robot::load_robot_description(o.robot);
    std::vector<NamedPath> read_files = robot_files("--robot", o.robot, robot);
    read_files.insert(read_files.end(), {{"--validate", o.validate}, {"--log-format", o.log_format.file}});
    for (const std::string& in : o.inputs) read_files.push_back({"--in", in});
    check_outputs({{"--output", o.output}}, read_files);
    read_files.push_back({"--output", o.output});
    check_output_directory({"--report", o.report}, read_files);  // written after the work: checked before it
    // Its blocked cross-validation and horizon simulations read one continuous record (docs/log-format.md).
    refuse_split(o.log_format, "diagnose");
    io::require_distinct_inputs("--in", o.inputs);  // one log twice (a link, a copy) would count its equations twice
    const auto model = robot::make_robot_model(robot);
    // Several logs (--in a --in b) are diagnosed together, on one sample period (the first log's).
    std::vector<io::CsvTable> tables;
    tables.reserve(o.inputs.size());  // the columns point into the tables: no reallocation
    std::vector<identify::LogColumns> logs;
    for (const std::string& in : o.inputs) {
        const double period = logs.empty() ? 0.0 : logs.front().sample_period;
        tables.push_back(read_log_table(in, o.log_format, robot_column_names(robot, o.time_column), o.quiet, period));
        logs.push_back(identify::log_columns(tables.back(), robot, o.time_column, o.time_tolerance));
        if (std::abs(logs.back().sample_period - logs.front().sample_period) > 1e-9 * logs.front().sample_period) {
            throw InputError(fmt::format("--in {}: sample period {} s differs from {} s of --in {}: logs diagnosed together need one", in,
                                         logs.back().sample_period, logs.front().sample_period, o.inputs.front()));
        }
    }
    const identify::LogColumns& log = logs.front();
    std::size_t samples = 0;
    for (const auto& l : logs) samples += l.samples();
    refuse_oversized_search(o.settings, log, *model, samples);
    std::unique_ptr<io::CsvTable> vtable;
    identify::LogColumns vlog;
    if (!o.validate.empty()) {
        vtable = std::make_unique<io::CsvTable>(read_log_table(o.validate, o.log_format, robot_column_names(robot, o.time_column), o.quiet, log.sample_period));
        vlog = identify::log_columns(*vtable, robot, o.time_column, o.time_tolerance);
        if (std::abs(vlog.sample_period - log.sample_period) > 1e-9 * log.sample_period) {
            throw InputError(fmt::format("--validate {}: sample period {} s differs from {} s of --in", o.validate, vlog.sample_period, log.sample_period));
        }
    }
    auto progress = [&](const std::string& line) {
        if (!o.quiet) fmt::print(stderr, "diagnose: {}\n", line);
    };
    o.settings.selection.search_delay = !o.no_delay;
    o.settings.catalogue.torque_delay = !o.no_delay;
    const diagnose::Diagnosis d = diagnose::diagnose_log(robot, *model, logs, o.validate.empty() ? nullptr : &vlog, o.settings, progress);
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
    cmd->add_option("--robot", o->robot, "robot description (YAML, as for identify)")->required()->check(file_path());
    cmd->add_option("--in", o->inputs,
                    "log (CSV: time column, the joints' position and torque columns); repeat it (--in a.csv --in b.csv) to diagnose several "
                    "logs together: each keeps its own edges, their equations are stacked as identify stacks them")
        ->expected(1)
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
        ->required()->check(file_path());
    cmd->add_option("--validate", o->validate, "held-out log for the selection and the before/after figures (default: blocked cross-validation)")->check(file_path());
    cmd->add_option("--format", o->format, "table (text) or json")->check(CLI::IsMember({"table", "json"}))->capture_default_str();
    cmd->add_option("--output,-o", o->output, "output file, '-' for standard output")->capture_default_str()->check(file_path(true));
    cmd->add_option("--report", o->report, "also write DIR/report.md with PNG plots of the residual vs velocity and position, before and after")->check(file_path());
    cmd->add_option("--time-column", o->time_column, "name of the time column (s)")->capture_default_str();
    add_time_tolerance_option(cmd, o->time_tolerance);
    add_log_format_options(cmd, o->log_format);
    add_diagnose_search_options(cmd, o->settings, o->no_delay);
    cmd->add_flag("--quiet", o->quiet, "no progress messages on stderr");
    cmd->callback([o] { run(*o); });
}

}  // namespace jacobid::cli
