// SPDX-License-Identifier: MIT
#pragma once
// identify --export-urdf / --export-robot: the identified model as files other tools (and jacobid) load.
// The physically consistent standard parameters (physical_identification.hpp) reproduce the identified base
// parameters exactly (base = K s); they are written
//   - into the robot's URDF (robot/urdf_export.hpp): inertials and <dynamics damping friction>, with what
//     URDF cannot carry (rotor inertia IAj, friction offset FOFFj, presliding level FDj, the Coulomb smoothing) in a
//     comment per joint;
//   - as a robot description (the YAML load_robot_description reads) that gives the identified model when
//     loaded: every standard value in `parameters` (for a urdf model whose URDF is exported too, the file
//     points to it and `parameters` keeps only what the URDF cannot carry), each joint's Coulomb smoothing
//     (and Dahl presliding displacement) fixed at the value identified with.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "identify/report/report.hpp"
#include "robot/robot_description.hpp"

namespace jacobid::identify {

struct ModelExportPaths {
    std::string urdf;   // --export-urdf; empty: not written
    std::string robot;  // --export-robot; empty: not written
    bool any() const { return !urdf.empty() || !robot.empty(); }
};

// Before identifying: InputError for a model without standard parameters (planar2r), --export-urdf with a
// description that is not a URDF model, or '-'. A path over an input (the description's own YAML or URDF: the
// prior would be lost; a log) or over the other export, or in a missing directory, is refused by the
// command's output guard (options/output_file.hpp, check_outputs).
void check_model_export(const ModelExportPaths& paths, const robot::RobotDescription& description);

struct ExportedModel {
    std::string urdf;   // the URDF text (empty when not asked for)
    std::string robot;  // the description's YAML text (empty when not asked for)
    // --export-urdf of a --semi-physical fit: bodies no mass distribution has (robot::impossible_inertias).
    std::vector<std::string> warnings;
    nlohmann::json summary;  // JSON "export": {method, constraint, urdf, robot, not_in_urdf, warnings}
};

// The files' texts from `result` (which must hold the physical fit) of `description`; log_source names the log
// in the files' header comments. InputError when the result has no standard parameters.
ExportedModel export_model(const ModelExportPaths& paths, const robot::RobotDescription& description, const MethodResult& result,
                           const std::string& log_source);

// The description that gives the identified model: `standard` (names, values) as its parameters, `alphas` per
// joint as its fixed Coulomb smoothing (and, when given, presliding_displacements as its fixed Dahl x_p); with
// `urdf_path` (a urdf model's exported URDF, as the description file will name it) only the parameters a URDF
// cannot carry (IAj, FOFFj, FDj) stay in `parameters`.
robot::RobotDescription identified_description(const robot::RobotDescription& description, const std::vector<std::string>& names,
                                               const Eigen::VectorXd& standard, const std::vector<double>& alphas, const std::string& urdf_path,
                                               const std::vector<double>& presliding_displacements = {});

// One line for the text report.
std::string describe_export(const nlohmann::json& summary);

}  // namespace jacobid::identify
