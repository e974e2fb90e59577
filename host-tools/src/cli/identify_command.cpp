// SPDX-License-Identifier: MIT
// jacobid identify: dynamic parameters of a robot from a log of joint positions and motor torques
// (Table II of the paper: X^, 2 sigma, %sigma_r), with the Jacobi pipeline, the Butterworth baseline or
// both side by side. The command parses and prints; the identification is the identify job (job/identify_job.hpp),
// which the Python module runs too.
#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include <algorithm>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>

#include "cli/command.hpp"
#include "core/free_memory.hpp"
#include "io/printable_text.hpp"
#include "job/identify_job.hpp"
#include "options/identify_options.hpp"
#include "options/option_checks.hpp"
#include "options/output_file.hpp"
#include "robot/base_parameter_report.hpp"
#include "robot/robot_description.hpp"

namespace jacobid::cli {
namespace {

// The options of the identification (options/identify_options.hpp) and what only the command line has.
struct IdentifyCommandOptions : IdentifyOptions {
    std::string format = "table";
    std::string output = "-";
    bool print_base = false;
};

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
void require_truth_of_the_model(const std::map<std::string, double>& truth, const std::vector<std::string>& names, const options::IdentifyOptions& o) {
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

std::vector<job::LogSource> sources_of(const std::vector<std::string>& paths) {
    std::vector<job::LogSource> sources;
    for (const std::string& path : paths) sources.push_back({path, std::nullopt});
    return sources;
}

void run(IdentifyCommandOptions o) {
    map_large_blocks();  // whole-log buffers returned when freed (core/free_memory.hpp)
    const robot::RobotDescription robot = robot::load_robot_description(o.robot);
    job::check_identify_files(o, robot, {{"--output", o.output}});
    const auto model = robot::make_robot_model(robot);
    if (o.print_base) {
        // The model alone: base parameters, regrouping relations and true values; no log needed.
        write_output(o.output, o.format == "json" ? robot::base_parameter_json(robot, *model).dump(2) + "\n" : robot::base_parameter_text(robot, *model));
        return;
    }
    if (o.inputs.empty()) throw InputError("--in is required (a log to identify from), unless --print-base");
    if (o.drive_gains.enabled) {
        job::resolve_threads(o);  // run_identify resolves them itself
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
                                               {o.first_input(), o.format, o.time_column, o.time_tolerance, o.quiet, &o.log_format, given}));
        return;
    }
    const std::map<std::string, double> truth = o.truth.empty() ? std::map<std::string, double>{} : read_truth(o.truth);
    if (!o.truth.empty()) require_truth_of_the_model(truth, model->parameter_names(), o);
    o.text_on_stdout = o.format == "table" && o.output == "-";
    std::optional<job::LogSource> validation;
    if (!o.validate.empty()) validation = job::LogSource{o.validate, std::nullopt};
    const job::IdentifyJobResult result = job::run_identify(robot, *model, o, sources_of(o.inputs), std::move(validation), truth);
    write_output(o.output, o.format == "json" ? job::to_json(result).dump(2) + "\n" : job::to_text(result));
}

}  // namespace

void add_identify_command(CLI::App& app) {
    auto o = std::make_shared<IdentifyCommandOptions>();
    CLI::App* cmd = app.add_subcommand("identify",
                                       "identify base dynamic parameters from a log (t, positions, torques) by least squares on the "
                                       "decimated inverse dynamic model; prints the paper's Table II");
    cmd->add_option("--robot", o->robot, "robot description (YAML, e.g. 'model: planar2r')")->required()->check(file_path());
    cmd->add_option("--in", o->inputs,
                    "log (CSV with a header: time column, the joints' position and torque columns); repeat it (--in a.csv --in b.csv) to "
                    "identify several logs together: each log keeps its own edges, their equations are stacked")
        ->expected(1)
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
        ->check(file_path());
    cmd->add_flag("--print-base", o->print_base,
                  "print the robot's base parameters with their regrouping relations (e.g. ZZ1R = ZZ1 + IA1 + 0.25*M2) and true values, "
                  "then exit (no --in needed)");
    cmd->add_option("--format", o->format, "table (Table II text) or json")->check(CLI::IsMember({"table", "json"}))->capture_default_str();
    cmd->add_option("--output,-o", o->output, "output file, '-' for standard output")->capture_default_str()->check(file_path(true));
    cmd->add_option("--truth", o->truth, "truth JSON (from jacobid simulate): adds the true values and errors to the table")->check(file_path());
    cmd->add_option("--validate", o->validate,
                    "second log: predict its torques with the identified parameters, report RMS errors; a log that holds a pose gets the "
                    "static (gravity) check per joint")
        ->check(file_path());
    add_identify_options(cmd, *o);
    cmd->callback([o] {
        finish_identify_options(*o);
        run(*o);
    });
}

}  // namespace jacobid::cli
