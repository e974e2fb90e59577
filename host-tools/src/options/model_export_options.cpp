// SPDX-License-Identifier: MIT
#include "options/model_export_options.hpp"

#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include "core/errors.hpp"
#include "options/option_checks.hpp"
#include "options/output_file.hpp"

namespace jacobid::options {
namespace {

void write_file(const char* option, const std::string& path, const std::string& text) {
    if (path.empty()) return;
    try {
        write_output(path, text);
    } catch (const InputError& e) {
        throw InputError(fmt::format("{} {}", option, e.what()));
    }
}

}  // namespace

void add_model_export_options(CLI::App* command, identify::ModelExportPaths& paths) {
    const char* implies =
        " Needs standard parameters: implies --physical unless --semi-physical is given; with --method both the first method's (jacobi) "
        "fit is written.";
    command->add_option("--export-urdf", paths.urdf,
                        std::string("write the robot's URDF (model urdf only) with the identified inertials (mass, centre of mass, inertia about it; "
                                    "links fixed to a moving link merged into it) and <dynamics damping=FV friction=FC>, everything else "
                                    "kept; rotor inertia, friction offset and Coulomb smoothing in a comment per joint.") +
                            implies)
        ->check(file_path());
    command->add_option("--export-robot", paths.robot,
                        std::string("write a robot description (YAML, model mdh or urdf) that loads as the identified model: standard "
                                    "values in parameters (with --export-urdf: that URDF and only what it cannot carry), each joint's "
                                    "Coulomb smoothing fixed.") +
                            implies)
        ->check(file_path());
}

nlohmann::json write_model_export(const identify::ModelExportPaths& paths, const robot::RobotDescription& description,
                                  const identify::MethodResult& result, const std::string& log_source) {
    const identify::ExportedModel exported = identify::export_model(paths, description, result, log_source);
    write_file("--export-urdf", paths.urdf, exported.urdf);
    write_file("--export-robot", paths.robot, exported.robot);
    for (const auto& w : exported.warnings) fmt::print(stderr, "jacobid identify: warning: --export-urdf {}: {}\n", paths.urdf, w);
    return exported.summary;
}

}  // namespace jacobid::options
