// SPDX-License-Identifier: MIT
#include "identify/report/model_export.hpp"

#include <fmt/core.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "core/errors.hpp"
#include "robot/urdf_export.hpp"
#include "jacobid/yaml/input_file.hpp"

namespace jacobid::identify {
namespace {

namespace fs = std::filesystem;

// The kind of a standard parameter name: "XX3" -> "XX", "FOFF1" -> "FOFF".
std::string kind_of(const std::string& standard_name) { return standard_name.substr(0, standard_name.find_first_of("0123456789")); }

// What a URDF cannot carry: rotor inertias, friction offsets, Dahl presliding levels (FDj), whatever comes
// next; inertials carry XX..M and <dynamics> FV, FC.
bool beyond_urdf(const std::string& standard_name) {
    static const std::set<std::string> carried{"XX", "XY", "XZ", "YY", "YZ", "ZZ", "MX", "MY", "MZ", "M", "FV", "FC"};
    return carried.count(kind_of(standard_name)) == 0;
}

// What the joint comment says of a value the URDF cannot carry.
std::string meaning(const std::string& kind) {
    if (kind == "IA") return "kg.m^2, rotor inertia on the joint axis: MuJoCo's joint armature";
    if (kind == "FOFF") return "N.m, constant torque offset";
    if (kind == "FD") return "N.m, Dahl presliding friction level (jacobid friction presliding: dahl)";
    if (kind == "FCL") return "N.m per N.m of gravity load, load-dependent Coulomb friction (jacobid friction coulomb_load)";
    return "see docs/identify.md";
}

// Whether it overwrites an input (the description's own files hold the prior) or the other export, and
// whether its directory exists, is the output guard's (options/output_file.hpp, check_outputs); here only what
// is particular to an export.
void check_path(const char* option, const std::string& path) {
    if (path == "-") throw InputError(fmt::format("{} -: expected a file path (standard output carries the report)", option));
}

std::string read_text(const std::string& path) { return yaml::read_input_file<InputError>(path, "URDF"); }

std::vector<double> joint_alphas(const robot::RobotDescription& description, const MethodResult& result) {
    if (result.coulomb_smoothing) return result.coulomb_smoothing->alphas();
    std::vector<double> alphas;
    for (const auto& sign : robot::joint_coulomb_signs(description)) alphas.push_back(sign.alpha);
    return alphas;
}

// Per joint, the comment beside its <dynamics>: the identified values a URDF has no place for.
std::vector<std::string> joint_notes(const robot::RobotDescription& description, const std::vector<std::string>& names, const Eigen::VectorXd& s,
                                     const std::vector<double>& alphas) {
    std::vector<std::string> notes;
    for (std::size_t j = 0; j < description.joints.size(); ++j) {
        std::string note = "jacobid, not in URDF:";
        for (std::size_t i = 0; i < names.size(); ++i) {
            const std::string kind = kind_of(names[i]);
            if (!beyond_urdf(names[i]) || names[i] != kind + std::to_string(j + 1)) continue;
            note += fmt::format(" {} = {:.17g} ({});", names[i], s[static_cast<Eigen::Index>(i)], meaning(kind));
        }
        if (description.coulomb.model == robot::CoulombModel::Sign) {
            note += " Coulomb friction = friction * sign(qd)";
        } else {
            note += fmt::format(" Coulomb friction = friction * 2/pi atan({:.17g} qd)", alphas[j]);
        }
        notes.push_back(note);
    }
    return notes;
}

}  // namespace

void check_model_export(const ModelExportPaths& paths, const robot::RobotDescription& description) {
    if (!paths.any()) return;
    const char* option = paths.urdf.empty() ? "--export-robot" : "--export-urdf";
    if (description.model != "mdh" && description.model != "urdf") {
        throw InputError(fmt::format("{}: model {} has no standard (per-link) parameters to export; describe the robot with model mdh or urdf",
                                     option, description.model));
    }
    if (!paths.urdf.empty() && description.model != "urdf") {
        throw InputError(fmt::format("--export-urdf {}: model {} has no URDF to carry the identified values (a URDF needs the links' geometry); "
                                     "use --export-robot, or describe the robot with model urdf",
                                     paths.urdf, description.model));
    }
    if (!paths.urdf.empty()) check_path("--export-urdf", paths.urdf);
    if (!paths.robot.empty()) check_path("--export-robot", paths.robot);
}

robot::RobotDescription identified_description(const robot::RobotDescription& description, const std::vector<std::string>& names,
                                               const Eigen::VectorXd& standard, const std::vector<double>& alphas, const std::string& urdf_path,
                                               const std::vector<double>& presliding_displacements) {
    robot::RobotDescription d = description;
    d.parameters.clear();
    for (std::size_t i = 0; i < names.size(); ++i) {
        if (urdf_path.empty() || beyond_urdf(names[i])) d.parameters.emplace_back(names[i], standard[static_cast<Eigen::Index>(i)]);
    }
    if (!urdf_path.empty()) d.urdf = urdf_path;
    // The model identified with, not a new choice on the next log.
    d.coulomb_alpha = alphas;
    d.coulomb_alpha_auto = false;
    if (!presliding_displacements.empty()) {
        d.presliding_displacements = presliding_displacements;
        d.presliding_displacement_auto = false;
    }
    return d;
}

ExportedModel export_model(const ModelExportPaths& paths, const robot::RobotDescription& description, const MethodResult& result,
                           const std::string& log_source) {
    if (!result.physical) throw InputError("--export-urdf / --export-robot: the fit has no standard parameters (it needs --physical or --semi-physical)");
    const PhysicalReport& physical = *result.physical;
    const std::vector<std::string>& names = physical.standard_names;
    const Eigen::VectorXd& s = physical.fit.standard;
    const std::vector<double> alphas = joint_alphas(description, result);
    const char* constraint = to_string(physical.fit.constraint);
    const char* method = to_string(result.info.method);
    const std::string header = fmt::format(
        "jacobid identify, {} fit of the {} method on {}: standard parameters that reproduce the identified base parameters, nearest "
        "the description's values (prior weight {}) where the log leaves freedom",
        constraint, method, log_source, physical.prior_weight);

    ExportedModel out;
    out.summary = {{"method", method}, {"constraint", constraint}};
    if (!paths.urdf.empty()) {
        const robot::UrdfExport values{names, s, header + "; inertials and <dynamics damping friction> are the identified ones",
                                       joint_notes(description, names, s, alphas)};
        out.urdf = robot::export_urdf(read_text(description.urdf), description.urdf, values);
        out.summary["urdf"] = paths.urdf;
        std::vector<std::string> joint_names;
        for (const auto& joint : description.joints) joint_names.push_back(joint.name);
        out.warnings = robot::impossible_inertias(values, joint_names);
    }
    if (!paths.robot.empty()) {
        std::string urdf_reference;
        if (!paths.urdf.empty()) {
            // Relative to the description file, as load_robot_description resolves it: the pair can be moved together.
            const fs::path urdf = fs::absolute(paths.urdf).lexically_normal();
            const fs::path relative = urdf.lexically_relative(fs::absolute(paths.robot).lexically_normal().parent_path());
            urdf_reference = relative.empty() ? urdf.string() : relative.string();
        }
        const std::vector<double> displacements = result.presliding_displacement ? result.presliding_displacement->displacement : std::vector<double>{};
        out.robot = "# " + header + "\n" + robot::to_yaml(identified_description(description, names, s, alphas, urdf_reference, displacements));
        out.summary["robot"] = paths.robot;
    }
    nlohmann::json beyond = nlohmann::json::object();
    for (std::size_t i = 0; i < names.size(); ++i) {
        if (beyond_urdf(names[i])) beyond[names[i]] = s[static_cast<Eigen::Index>(i)];
    }
    out.summary["not_in_urdf"] = beyond;
    out.summary["warnings"] = out.warnings;
    return out;
}

std::string describe_export(const nlohmann::json& summary) {
    std::string files;
    for (const char* key : {"urdf", "robot"}) {
        if (summary.contains(key)) files += fmt::format("{}{}", files.empty() ? "" : ", ", summary[key].get<std::string>());
    }
    return fmt::format("exported the {} method's --{} standard parameters: {}\n", summary["method"].get<std::string>(),
                       summary["constraint"].get<std::string>(), files);
}

}  // namespace jacobid::identify
