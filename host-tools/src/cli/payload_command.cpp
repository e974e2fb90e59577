// SPDX-License-Identifier: MIT
// jacobid payload: the mass, centre of mass and inertia of a tool on the last link from a run with it, the arm
// held at its identified values (payload/payload_estimate.hpp; docs/identify.md, "Payload").
#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include <memory>

#include "cli/command.hpp"
#include "options/option_checks.hpp"
#include "options/output_file.hpp"
#include "options/payload_options.hpp"
#include "options/robot_files.hpp"
#include "payload/payload_export.hpp"
#include "payload/payload_report.hpp"

namespace jacobid::cli {
namespace {

struct PayloadCommandOptions : PayloadOptions {
    std::string output = "-", export_urdf, export_robot;
    bool json = false;
};

void run(const PayloadCommandOptions& o) {
    const robot::RobotDescription robot = robot::load_robot_description(o.robot);
    std::vector<NamedPath> read_files = robot_files("--robot", o.robot, robot);
    read_files.insert(read_files.end(), {{"--arm", o.arm}, {"--in", o.in}, {"--unloaded", o.unloaded}, {"--log-format", o.log_format.file}});
    check_outputs({{"--output", o.output}, {"--export-urdf", o.export_urdf}, {"--export-robot", o.export_robot}}, read_files);
    const PayloadRun r = run_payload(o);
    const payload::PayloadEstimate& e = r.estimate;
    if (!o.export_urdf.empty()) write_output(o.export_urdf, payload::urdf_fragment(e, r.arm.description));
    if (!o.export_robot.empty()) {
        // identify's JSON holds base parameters only: the file then carries --robot's own standard values.
        const std::string arm_text = r.arm.base_only ? fmt::format("{} (its standard parameters; {} holds base parameters only)", o.robot, r.arm.source)
                                                     : r.arm.source;
        write_output(o.export_robot, fmt::format("# {} with the payload estimated by jacobid payload from {} on its last link\n", arm_text, o.in) +
                                         robot::to_yaml(payload::with_payload(r.arm, e.standard)));
    }
    write_output(o.output, o.json ? payload::payload_json(e).dump(2) + "\n" : payload::payload_text(e));
}

}  // namespace

void add_payload_command(CLI::App& app) {
    auto o = std::make_shared<PayloadCommandOptions>();
    CLI::App* cmd = app.add_subcommand("payload",
                                       "identify a payload on the last link (mass, centre of mass, inertia about it) from a run with it, the arm held "
                                       "at its identified values; with --unloaded, from the difference of the runs with and without it");
    cmd->add_option("--robot", o->robot, "robot description (YAML, as for identify): joints, log columns, kinematics")->required()->check(file_path());
    cmd->add_option("--arm", o->arm,
                    "the identified arm: `jacobid identify --format json` output (values and std) or a robot description such as "
                    "identify --export-robot writes (values only)")
        ->required()
        ->check(file_path());
    cmd->add_option("--in", o->in, "the run with the payload (CSV or --log-format)")->required()->check(file_path());
    cmd->add_option("--unloaded", o->unloaded,
                    "the same trajectory without the payload: the payload is estimated from the difference of the two runs after aligning "
                    "them in time (the shift is reported)")
        ->check(file_path());
    cmd->add_flag("--json", o->json, "JSON instead of the text table");
    cmd->add_option("--output,-o", o->output, "output file, '-' for standard output")->capture_default_str()->check(file_path(true));
    cmd->add_option("--export-urdf", o->export_urdf, "write a URDF <joint>+<link> fragment of the payload")->check(file_path());
    cmd->add_option("--export-robot", o->export_robot, "write the arm's robot description with the payload on its last link (YAML)")->check(file_path());
    add_payload_options(cmd, *o);
    cmd->add_flag("--quiet", o->quiet, "no progress messages on stderr");
    cmd->callback([o] { run(*o); });
}

}  // namespace jacobid::cli
