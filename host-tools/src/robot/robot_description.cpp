// SPDX-License-Identifier: MIT
#include "robot/robot_description.hpp"

#include <fmt/core.h>
#include <fmt/ranges.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>
#include <stdexcept>

#include "core/errors.hpp"
#include "robot/package_uri.hpp"
#include "robot/planar2r_model.hpp"
#include "robot/presliding_model.hpp"
#include "robot/serial_robot_model.hpp"
#include "robot/urdf_chain.hpp"
#include "jacobid/yaml/yaml_section.hpp"
#include "jacobid/yaml/input_file.hpp"

namespace jacobid::robot {
namespace {
using Section = yaml::YamlSection<InputError>;

constexpr const char* kKnownModels = "planar2r, mdh, urdf";

std::vector<JointDescription> default_joints(int count) {
    std::vector<JointDescription> joints;
    for (int j = 1; j <= count; ++j) joints.push_back({fmt::format("j{}", j), fmt::format("q{}", j), fmt::format("tau{}", j), -2.5, 2.5});
    return joints;
}

// name, position, torque, limits of one joint map (the keys every model shares); true if limits were given.
bool read_joint_columns(Section& s, JointDescription& joint) {
    joint.name = s.text("name", joint.name);
    joint.position_column = s.text("position", joint.position_column);
    joint.torque_column = s.text("torque", joint.torque_column);
    if (!s.has("limits")) {
        s.mark_used("limits");
        return false;
    }
    const YAML::Node limits = s.list("limits", 2, 2, "numbers [lower, upper] (rad or m)");
    joint.lower_limit = s.number_element(limits[0], "limits", "rad or m");
    joint.upper_limit = s.number_element(limits[1], "limits", "rad or m");
    if (joint.lower_limit > joint.upper_limit) s.fail("limits", fmt::format("lower {} > upper {}", joint.lower_limit, joint.upper_limit));
    joint.limits_given = true;
    return true;
}

// The joints list: absent (defaults), or exactly `count` entries (names or maps read by `read`).
template <typename ReadJoint>
void read_joint_list(Section& top, int count, const std::string& of, ReadJoint read) {
    if (!top.has("joints")) {
        top.mark_used("joints");
        return;
    }
    const YAML::Node joints = top.list("joints", static_cast<std::size_t>(count), static_cast<std::size_t>(count), of);
    for (int j = 0; j < count; ++j) read(joints[static_cast<std::size_t>(j)], j, fmt::format("{}[{}]", top.qualified("joints"), j));
}

void parse_planar2r_joints(Section& top, RobotDescription& d) {
    d.joints = default_joints(2);
    read_joint_list(top, 2, "joints (names or maps) for model planar2r", [&](const YAML::Node& node, int j, const std::string& path) {
        JointDescription& joint = d.joints[static_cast<std::size_t>(j)];
        if (node.IsScalar()) {
            joint.name = node.as<std::string>();
            return;
        }
        Section s(top.source(), node, path);
        read_joint_columns(s, joint);
        s.reject_unknown();
    });
}

void parse_mdh_joints(Section& top, RobotDescription& d) {
    if (!top.has("joints")) top.fail(top.node(), "joints", "missing (required): model mdh needs one MDH row per joint (sigma, alpha, d, theta, r)");
    const YAML::Node joints = top.list("joints", 1, kMaxSerialJoints, "MDH rows");
    const int n = static_cast<int>(joints.size());
    d.joints = default_joints(n);
    KinematicChain<kMaxSerialJoints> check;
    for (int j = 0; j < n; ++j) {
        Section s(top.source(), joints[static_cast<std::size_t>(j)], fmt::format("joints[{}]", j));
        JointDescription& joint = d.joints[static_cast<std::size_t>(j)];
        const bool has_limits = read_joint_columns(s, joint);
        MdhJoint row;
        if (!s.has("sigma")) s.fail(s.node(), "sigma", "missing (required): 0 revolute, 1 prismatic");
        const long sigma = s.integer("sigma", 0, std::numeric_limits<long>::min(), std::numeric_limits<long>::max());
        if (sigma != 0 && sigma != 1) s.fail("sigma", fmt::format("must be 0 (revolute) or 1 (prismatic), got {}", sigma));
        row.type = sigma == 1 ? JointType::Prismatic : JointType::Revolute;
        if (row.type == JointType::Prismatic && !has_limits) s.fail(s.node(), "limits", "required for a prismatic joint: [lower, upper] in m");
        row.alpha = s.number("alpha", 0.0, "rad");
        row.d = s.number("d", 0.0, "m");
        row.theta = s.number("theta", 0.0, "rad");
        row.r = s.number("r", 0.0, "m");
        // Khalil's a(j): 0 is the base, k is joint k; default: the previous joint (a serial chain).
        const long antecedent = s.integer("antecedent", j, std::numeric_limits<long>::min(), std::numeric_limits<long>::max());
        if (antecedent < 0 || antecedent > j) s.fail("antecedent", fmt::format("must be 0 (base) to {} (an earlier joint), got {}", j, antecedent));
        row.antecedent = static_cast<int>(antecedent) - 1;
        s.reject_unknown();
        const ChainError e = check.add(to_chain_joint(row));
        if (e != ChainError::Ok) s.fail(s.node(), "", to_string(e));
        d.mdh.push_back(row);
        d.chain.push_back(to_chain_joint(row));
    }
}

std::string directory_of(const std::string& path) {
    const auto slash = path.rfind('/');
    return slash == std::string::npos ? std::string() : path.substr(0, slash + 1);
}

void parse_urdf(Section& top, RobotDescription& d) {
    if (!top.has("urdf")) top.fail(top.node(), "urdf", "missing (required): model urdf needs 'urdf: <file.urdf>' (relative to this file)");
    std::string file = top.text("urdf", "");
    const std::string& source = top.source();
    if (is_package_uri(file)) {
        const ResolvedPackageUri resolved = resolve_package_uri(file);
        if (resolved.path.empty()) top.fail("urdf", fmt::format("'{}': {}", file, resolved.why));
        file = resolved.path;
    }
    // Absolute, so that to_yaml() (stored in simulation truth files) still finds it from elsewhere.
    std::error_code absolute_error;
    d.urdf = (!file.empty() && file[0] == '/') ? file : directory_of(source) + file;
    const auto absolute = std::filesystem::absolute(d.urdf, absolute_error);
    if (!absolute_error) d.urdf = absolute.lexically_normal().string();
    // Regular files only: a description must not make the tool read a device or a pipe forever.
    std::error_code ec;
    if (!std::filesystem::is_regular_file(d.urdf, ec)) top.fail("urdf", fmt::format("'{}' is not a readable file", d.urdf));
    UrdfChain chain = load_urdf_chain(d.urdf);
    const int n = static_cast<int>(chain.joints.size());
    if (n > kMaxSerialJoints) throw InputError(fmt::format("{}: {} movable joints, at most {} are supported", d.urdf, n, kMaxSerialJoints));
    d.chain = chain.joints;
    d.model_parameters = chain.standard_parameters;
    d.joints = default_joints(n);
    for (int j = 0; j < n; ++j) {
        auto& joint = d.joints[static_cast<std::size_t>(j)];
        joint.name = chain.names[static_cast<std::size_t>(j)];
        joint.lower_limit = chain.limits[static_cast<std::size_t>(j)].first;
        joint.upper_limit = chain.limits[static_cast<std::size_t>(j)].second;
        joint.limits_given = chain.limits_given[static_cast<std::size_t>(j)];
    }
    read_joint_list(top, n, fmt::format("joint maps {{name, position, torque, limits}} (the movable joints of {})", d.urdf),
                    [&](const YAML::Node& node, int j, const std::string& path) {
                        Section s(source, node, path);
                        read_joint_columns(s, d.joints[static_cast<std::size_t>(j)]);
                        s.reject_unknown();
                    });
}

// A friction shape option that is `auto`, one positive number for every joint, or a list with one per
// joint (friction.alpha, friction.presliding_displacement).
void read_auto_or_per_joint(Section& friction, const char* key, const char* unit, std::size_t joints, bool& is_auto, double& common,
                            std::vector<double>& per_joint) {
    if (!friction.has(key)) {
        friction.mark_used(key);
        return;
    }
    const YAML::Node node = friction.get(key);
    const auto positive = [&](const YAML::Node& n) {
        const double v = friction.number_element(n, key, unit);
        if (!(v > 0.0)) friction.fail(n, key, fmt::format("must be > 0 {}", unit));
        return v;
    };
    if (node.IsScalar() && node.Scalar() == "auto") {
        is_auto = true;
    } else if (node.IsSequence()) {
        if (node.size() != joints) friction.fail(node, key, fmt::format("must be auto, a number, or a list of {} numbers (one per joint)", joints));
        for (const auto& entry : node) per_joint.push_back(positive(entry));
        is_auto = false;
    } else if (node.IsScalar()) {
        common = positive(node);
        is_auto = false;
    } else {
        friction.fail(node, key, fmt::format("expected auto, a number or a list of numbers ({})", unit));
    }
}

std::unique_ptr<RobotModel> make_rigid_body_model(const RobotDescription& d);

// Names a `parameters:` entry may take beyond the model's own: the presliding levels FDj.
std::vector<std::string> presliding_names(const RobotDescription& d) {
    std::vector<std::string> names;
    if (d.presliding) {
        for (std::size_t j = 0; j < d.joints.size(); ++j) names.push_back(fmt::format("FD{}", j + 1));
    }
    return names;
}

// ... and the load-dependent Coulomb levels FCLj (every joint; one that gravity never loads has no column).
std::vector<std::string> load_friction_names(const RobotDescription& d) {
    std::vector<std::string> names;
    if (d.coulomb_load != CoulombLoad::none) {
        for (std::size_t j = 0; j < d.joints.size(); ++j) names.push_back(fmt::format("FCL{}", j + 1));
    }
    return names;
}

// The description's `parameters:` split into those named in `names` (returned) and the rest (kept in `d`).
std::vector<std::pair<std::string, double>> take_parameters(RobotDescription& d, const std::vector<std::string>& names) {
    std::vector<std::pair<std::string, double>> taken, kept;
    for (const auto& entry : d.parameters) (std::find(names.begin(), names.end(), entry.first) == names.end() ? kept : taken).push_back(entry);
    d.parameters = std::move(kept);
    return taken;
}

StandardParameterOptions options_of(const RobotDescription& d) {
    StandardParameterOptions options;
    options.coulomb = d.coulomb;
    options.rotor_inertia = d.rotor_inertia;
    options.friction_offset = d.friction_offset;
    return options;
}

}  // namespace

RobotDescription default_planar2r_description() {
    RobotDescription d;
    d.joints = default_joints(2);
    return d;
}

RobotDescription parse_robot_description(const std::string& yaml_text, const std::string& source) {
    const YAML::Node root = yaml::load<InputError>(yaml_text, source);
    if (!root.IsMap()) throw InputError(fmt::format("{}: expected a YAML map with at least 'model: planar2r'", source));
    Section top(source, root, "");
    RobotDescription d;
    d.source = source;
    if (!top.has("model")) top.fail(root, "model", fmt::format("missing (required): one of {}", kKnownModels));
    d.model = top.choice("model", "", {"planar2r", "mdh", "urdf"});
    const auto only_for = [&](const char* key, bool allowed, const char* models) {
        if (top.has(key) && !allowed) top.fail(key, fmt::format("is only for model {}", models));
    };
    only_for("L1", d.model == "planar2r", "planar2r");
    only_for("gravity", d.serial(), "mdh or urdf");
    only_for("urdf", d.model == "urdf", "urdf");
    d.L1 = top.positive("L1", d.L1, "link length in m");
    if (d.model == "planar2r") parse_planar2r_joints(top, d);
    if (d.model == "mdh") parse_mdh_joints(top, d);
    if (d.model == "urdf") parse_urdf(top, d);
    if (top.has("gravity")) {
        const YAML::Node gravity = top.list("gravity", 3, 3, "numbers [gx, gy, gz] in m/s^2");
        for (std::size_t k = 0; k < 3; ++k) d.gravity[static_cast<Eigen::Index>(k)] = top.number_element(gravity[k], "gravity", "m/s^2");
        // Bounded where it is read, for every command: 1e308 along an axis overflowed the base-parameter
        // search into "no moving joint" in identify, a wrong cause (simulate's own check came later).
        constexpr double kMaxGravity = 1e3;  // m/s^2, as robot/simulated_parameters.cpp
        if (d.gravity.norm() > kMaxGravity) {
            top.fail(gravity, "gravity", fmt::format("[{}]: expected a vector of at most {:g} m/s^2", fmt::join(d.gravity, ", "), kMaxGravity));
        }
    }
    top.mark_used("gravity");
    top.mark_used("friction");
    if (top.has("friction")) {
        Section friction = top.child("friction");
        d.coulomb.model = friction.choice("coulomb", d.coulomb.model == CoulombModel::Sign ? "sign" : "smooth", {"sign", "smooth"}) == "sign"
                              ? CoulombModel::Sign
                              : CoulombModel::SmoothAtan;
        read_auto_or_per_joint(friction, "alpha", "s/rad", d.joints.size(), d.coulomb_alpha_auto, d.coulomb.alpha, d.coulomb_alpha);
        d.friction_offset = friction.boolean("offset", d.friction_offset);
        const std::string load = friction.choice("coulomb_load", to_string(d.coulomb_load), {"none", "abs", "square"});
        d.coulomb_load = load == "abs" ? CoulombLoad::abs : load == "square" ? CoulombLoad::square : CoulombLoad::none;
        d.presliding = friction.choice("presliding", d.presliding ? "dahl" : "none", {"none", "dahl"}) == "dahl";
        for (const char* key : {"presliding_displacement", "presliding_play"}) {
            if (friction.has(key) && !d.presliding) friction.fail(key, "needs presliding: dahl");
        }
        read_auto_or_per_joint(friction, "presliding_displacement", "rad", d.joints.size(), d.presliding_displacement_auto,
                               d.presliding_displacement, d.presliding_displacements);
        if (friction.has("presliding_play")) {
            d.presliding_play = friction.number("presliding_play", d.presliding_play);
            if (!(d.presliding_play >= 0.0)) friction.fail("presliding_play", "must be >= 0 rad (the play operator's total width)");
        }
        friction.mark_used("presliding_play");
        friction.reject_unknown();
    }
    d.rotor_inertia = top.boolean("rotor_inertia", d.rotor_inertia);
    top.mark_used("parameters");
    if (top.has("parameters")) {
        Section parameters = top.child("parameters");
        // Serial robots take standard parameters (the base ones are derived); planar2r takes its base parameters.
        std::vector<std::string> known =
            d.serial() ? standard_parameter_names(static_cast<int>(d.chain.size()), options_of(d)) : make_robot_model(d)->parameter_names();
        if (d.serial()) {
            for (auto& name : presliding_names(d)) known.push_back(std::move(name));
        }
        for (auto& name : load_friction_names(d)) known.push_back(std::move(name));
        for (const auto& entry : parameters.node()) {
            if (!entry.first.IsScalar()) parameters.fail(entry.first, "", "expected a parameter name, found a list or map used as a key");
            const std::string name = entry.first.Scalar();
            if (std::find(known.begin(), known.end(), name) == known.end()) {
                std::string list;
                for (const auto& n : known) list += (list.empty() ? "" : ", ") + n;
                throw InputError(fmt::format("{}: unknown parameter '{}' (this model has: {})", yaml::where(source, entry.first), name, list));
            }
            d.parameters.emplace_back(name, parameters.number(name, 0.0));
        }
        parameters.reject_unknown();  // a parameter given twice
    }
    top.mark_used("controller");
    if (top.has("controller")) d.controller = parse_controller(source, root["controller"], d.joints.size());
    top.reject_unknown();
    return d;
}

RobotDescription load_robot_description(const std::string& path) {
    return parse_robot_description(yaml::read_input_file<InputError>(path, "robot description"), path);
}

std::vector<CoulombSign> joint_coulomb_signs(const RobotDescription& d) {
    std::vector<CoulombSign> signs(d.joints.size(), d.coulomb);
    for (std::size_t j = 0; j < signs.size() && j < d.coulomb_alpha.size(); ++j) signs[j].alpha = d.coulomb_alpha[j];
    return signs;
}

namespace {
// `nominal` (the description's rigid-body model) with load-dependent Coulomb friction of `law`, its
// reference gravity from the description's own rigid-body values (URDF inertials, `parameters:`).
std::unique_ptr<LoadFrictionModel> with_load_friction(const RobotDescription& d, std::unique_ptr<RobotModel> nominal, CoulombLoad law) {
    RobotDescription rigid = d;
    take_parameters(rigid, load_friction_names(d));
    take_parameters(rigid, presliding_names(d));
    rigid.coulomb_load = CoulombLoad::none;
    const Eigen::VectorXd reference = true_parameters(rigid, *nominal);
    return std::make_unique<LoadFrictionModel>(std::move(nominal), law, reference, joint_coulomb_signs(d));
}
}  // namespace

std::shared_ptr<const LoadFrictionModel> gravity_load_reference(const RobotDescription& d) {
    try {
        return with_load_friction(d, make_rigid_body_model(d), CoulombLoad::abs);
    } catch (const std::invalid_argument&) {
        return nullptr;  // no joint loaded
    }
}

std::unique_ptr<RobotModel> make_robot_model(const RobotDescription& d) {
    std::unique_ptr<RobotModel> nominal = make_rigid_body_model(d);
    if (d.coulomb_load != CoulombLoad::none) {
        try {
            nominal = with_load_friction(d, std::move(nominal), d.coulomb_load);
        } catch (const std::invalid_argument& e) {
            throw InputError(fmt::format("{}: friction: coulomb_load: {}", d.source, e.what()));
        }
    }
    if (!d.presliding) return nominal;
    return std::make_unique<PreslidingModel>(std::move(nominal), presliding_settings(d));
}

PreslidingSettings presliding_settings(const RobotDescription& d) {
    PreslidingSettings s;
    s.displacement.assign(d.joints.size(), d.presliding_displacement);
    for (std::size_t j = 0; j < s.displacement.size() && j < d.presliding_displacements.size(); ++j) s.displacement[j] = d.presliding_displacements[j];
    s.play_width = d.presliding_play;
    return s;
}

namespace {
// The model without friction memory.
std::unique_ptr<RobotModel> make_rigid_body_model(const RobotDescription& d) {
    if (d.model == "planar2r") {
        Planar2RConfig config;
        config.L1 = d.L1;
        config.coulomb = d.coulomb;
        config.friction_offset = d.friction_offset;
        config.rotor_inertia = d.rotor_inertia;
        return std::make_unique<Planar2RModel>(config, joint_coulomb_signs(d));
    }
    if (d.serial()) {
        SerialRobotConfig config;
        config.name = d.model;
        config.joints = d.chain;
        config.gravity = d.gravity;
        config.options = options_of(d);
        config.joint_coulomb = joint_coulomb_signs(d);
        try {
            return std::make_unique<SerialRobotModel>(std::move(config));
        } catch (const std::invalid_argument& e) {
            throw InputError(fmt::format("{}: {}", d.source, e.what()));
        } catch (const std::runtime_error& e) {
            // The base-parameter QR could not decide the rank: lengths spanning many orders of magnitude
            // (e.g. an offset of 1.8e8 m beside 0.3 m links, found by fuzz_robot_description).
            throw InputError(fmt::format("{}: {} (check the lengths in the description: they are in m)", d.source, e.what()));
        }
    }
    throw InputError(fmt::format("{}: unknown model '{}' (known models: {})", d.source, d.model, kKnownModels));
}
}  // namespace

Eigen::VectorXd standard_values(const RobotDescription& d, const SerialRobotModel& serial) {
    Eigen::VectorXd standard = Eigen::VectorXd::Zero(serial.standard_parameter_count());
    for (const auto* list : {&d.model_parameters, &d.parameters}) {
        for (const auto& [name, value] : *list) {
            const int index = serial.standard_index(name);
            if (index < 0) throw InputError(fmt::format("{}: parameters: model {} has no standard parameter '{}'", d.source, serial.model_name(), name));
            standard[index] = value;
        }
    }
    return standard;
}

namespace {
// A wrapper's values: the wrapped model's (`inner`), then the levels it appends (`level_names`: FDj, FCLj) from
// `parameters` (0 when not given). `why_missing` explains a given level the wrapper has no column for.
Eigen::VectorXd with_appended_levels(const RobotDescription& d, const std::vector<std::string>& level_names, const RobotModel& inner,
                                     const RobotModel& model, const char* why_missing) {
    RobotDescription rigid = d;
    const std::vector<std::pair<std::string, double>> levels = take_parameters(rigid, level_names);
    const Eigen::VectorXd x0 = true_parameters(rigid, inner);
    Eigen::VectorXd x = Eigen::VectorXd::Zero(model.parameter_count());
    x.head(x0.size()) = x0;
    for (const auto& [name, value] : levels) {
        const int index = model.parameter_index(name);
        if (index < 0) throw InputError(fmt::format("{}: parameters: {}: {}", d.source, name, why_missing));
        x[index] = value;
    }
    return x;
}
}  // namespace

Eigen::VectorXd true_parameters(const RobotDescription& d, const RobotModel& model) {
    if (const auto* presliding = dynamic_cast<const PreslidingModel*>(&model)) {
        return with_appended_levels(d, presliding_names(d), presliding->nominal(), model, "the model has no such presliding level");
    }
    if (const auto* loaded = dynamic_cast<const LoadFrictionModel*>(&model)) {
        return with_appended_levels(d, load_friction_names(d), loaded->nominal(), model,
                                    "gravity never loads that joint under the description's parameters, so it has no load-dependent Coulomb friction");
    }
    if (const auto* serial = dynamic_cast<const SerialRobotModel*>(&model)) return serial->base_values(standard_values(d, *serial));
    Eigen::VectorXd x = Eigen::VectorXd::Zero(model.parameter_count());
    if (const auto* planar = dynamic_cast<const Planar2RModel*>(&model)) {
        const auto table = paper_table2_parameters(*planar);
        for (int c = 0; c < model.parameter_count(); ++c) x[c] = table[static_cast<std::size_t>(c)];
    }
    for (const auto& [name, value] : d.parameters) {
        const int index = model.parameter_index(name);
        if (index < 0) throw InputError(fmt::format("{}: parameters: model {} has no parameter '{}'", d.source, model.model_name(), name));
        x[index] = value;
    }
    return x;
}

}  // namespace jacobid::robot
