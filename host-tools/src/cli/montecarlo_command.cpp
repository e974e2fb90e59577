// SPDX-License-Identifier: MIT
// jacobid montecarlo: N simulated runs of a robot description (run k: trajectory seed S + k, noise seed
// S2 + k), each identified as `jacobid identify` would, and per method and parameter the mean error with its
// standard error, the spread of the estimates against the reported std and the coverage of the truth by
// +-2 reported std (docs/montecarlo.md). How users check a setup before spending robot time.
#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include <memory>

#include "cli/command.hpp"
#include "options/montecarlo_options.hpp"
#include "options/option_checks.hpp"
#include "options/output_file.hpp"
#include "options/robot_files.hpp"
#include "montecarlo/study.hpp"
#include "montecarlo/study_report.hpp"
#include "robot/robot_description.hpp"

namespace jacobid::cli {
namespace {

// The command's own options beside the study's (options/montecarlo_options.hpp): its files and output format.
struct MonteCarloCommandOptions : MonteCarloOptions {
    std::string format = "table";
    std::string output = "-";
    std::string report;
};

void run(const MonteCarloCommandOptions& o) {
    const robot::RobotDescription description = o.robot.empty() ? robot::default_planar2r_description() : robot::load_robot_description(o.robot);
    std::vector<NamedPath> files = robot_files("--robot", o.robot, description);
    check_outputs({{"--output", o.output}}, files);
    files.push_back({"--output", o.output});
    check_output_directory({"--report", o.report}, files);  // written after the work: checked before it
    montecarlo::StudySettings s = study_settings(o);
    if (!o.quiet) s.progress = [](int finished, int runs) { fmt::print(stderr, "run {}/{}\n", finished, runs); };
    const montecarlo::Study study = montecarlo::run_study(s);
    const montecarlo::StudyContext context = study_context(o, s);
    write_output(o.output, o.format == "json" ? montecarlo::to_json(study, context).dump(2) + "\n" : montecarlo::format_table(study, context));
    if (!o.report.empty()) montecarlo::write_report(o.report, study, context);
}

}  // namespace

void add_montecarlo_command(CLI::App& app) {
    auto o = std::make_shared<MonteCarloCommandOptions>();
    CLI::App* cmd = app.add_subcommand("montecarlo",
                                       "N simulated runs of a robot (different seeds), each identified as identify would; per method and "
                                       "parameter: mean error and its standard error, spread of the estimates vs the reported std, coverage "
                                       "of the truth by +-2 reported std (docs/montecarlo.md)");
    cmd->add_option("--robot", o->robot, "robot description (YAML); default: planar2r, L1 0.5 m, smoothed Coulomb friction alpha 100 (auto in identification)")->check(file_path());
    add_montecarlo_options(cmd, *o);
    cmd->add_option("--format", o->format, "table (text) or json (with every run's estimates)")->check(CLI::IsMember({"table", "json"}))->capture_default_str();
    cmd->add_option("--output,-o", o->output, "output file, '-' for standard output")->capture_default_str()->check(file_path(true));
    cmd->add_option("--report", o->report, "also write DIR/report.md and DIR/montecarlo_<method>.png (normalized errors with the +-2 band)")->check(file_path());
    cmd->callback([o] { run(*o); });
}

}  // namespace jacobid::cli
