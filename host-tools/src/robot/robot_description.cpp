// SPDX-License-Identifier: MIT
#include "robot/robot_description.hpp"

#include <fmt/core.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>

#include "core/errors.hpp"
#include "robot/planar2r_model.hpp"
#include "robot/serial_robot_model.hpp"
#include "robot/urdf_chain.hpp"
#include "robot/yaml_fields.hpp"

namespace jacobid::robot {
namespace {
using namespace yaml_fields;

constexpr const char* kKnownModels = "planar2r, mdh, urdf";

std::vector<JointDescription> default_joints(int count) {
    std::vector<JointDescription> joints;
    for (int j = 1; j <= count; ++j) joints.push_back({fmt::format("j{}", j), fmt::format("q{}", j), fmt::format("tau{}", j), -2.5, 2.5});
    return joints;
}

bool is_serial(const std::string& model) { return model == "mdh" || model == "urdf"; }

// name, position, torque, limits of one joint map (the keys every model shares).
void read_joint_columns(const std::string& source, const YAML::Node& node, JointDescription& joint, bool& has_limits) {
    if (node["name"]) joint.name = text(source, node["name"], "name");
    if (node["position"]) joint.position_column = text(source, node["position"], "position");
    if (node["torque"]) joint.torque_column = text(source, node["torque"], "torque");
    if (const YAML::Node limits = node["limits"]) {
        if (!limits.IsSequence() || limits.size() != 2) throw InputError(fmt::format("{}: 'limits' must be [lower, upper]", where(source, limits)));
        joint.lower_limit = number(source, limits[0], "limits");
        joint.upper_limit = number(source, limits[1], "limits");
        if (joint.lower_limit > joint.upper_limit) {
            throw InputError(fmt::format("{}: 'limits' lower {} > upper {}", where(source, limits), joint.lower_limit, joint.upper_limit));
        }
        has_limits = true;
    }
}

void parse_planar2r_joints(const std::string& source, const YAML::Node& joints, RobotDescription& d) {
    const int joint_count = 2;
    d.joints = default_joints(joint_count);
    if (!joints) return;
    if (!joints.IsSequence() || static_cast<int>(joints.size()) != joint_count) {
        throw InputError(fmt::format("{}: 'joints' must be a list of {} joints for model {}", where(source, joints), joint_count, d.model));
    }
    for (int j = 0; j < joint_count; ++j) {
        const YAML::Node node = joints[static_cast<std::size_t>(j)];
        JointDescription& joint = d.joints[static_cast<std::size_t>(j)];
        if (node.IsScalar()) {
            joint.name = node.as<std::string>();
            continue;
        }
        if (!node.IsMap()) throw InputError(fmt::format("{}: joint {} must be a name or a map", where(source, node), j + 1));
        check_keys(source, node, {"name", "position", "torque", "limits"}, fmt::format("joint {}", j + 1));
        bool has_limits = false;
        read_joint_columns(source, node, joint, has_limits);
    }
}

void parse_mdh_joints(const std::string& source, const YAML::Node& joints, RobotDescription& d) {
    if (!joints) throw InputError(fmt::format("{}: model mdh needs 'joints' (one MDH row per joint: sigma, alpha, d, theta, r)", source));
    if (!joints.IsSequence() || joints.size() < 1 || static_cast<int>(joints.size()) > kMaxSerialJoints) {
        throw InputError(fmt::format("{}: 'joints' must be a list of 1 to {} MDH rows", where(source, joints), kMaxSerialJoints));
    }
    const int n = static_cast<int>(joints.size());
    d.joints = default_joints(n);
    KinematicChain<kMaxSerialJoints> check;
    for (int j = 0; j < n; ++j) {
        const YAML::Node node = joints[static_cast<std::size_t>(j)];
        const std::string what = fmt::format("joint {}", j + 1);
        if (!node.IsMap()) throw InputError(fmt::format("{}: {} must be a map {{name, sigma, alpha, d, theta, r, ...}}", where(source, node), what));
        check_keys(source, node, {"name", "sigma", "alpha", "d", "theta", "r", "antecedent", "limits", "position", "torque"}, what);
        JointDescription& joint = d.joints[static_cast<std::size_t>(j)];
        bool has_limits = false;
        read_joint_columns(source, node, joint, has_limits);
        MdhJoint row;
        if (!node["sigma"]) throw InputError(fmt::format("{}: {} needs 'sigma' (0: revolute, 1: prismatic)", where(source, node), what));
        const int sigma = integer(source, node["sigma"], "sigma");
        if (sigma != 0 && sigma != 1) {
            throw InputError(fmt::format("{}: 'sigma' must be 0 (revolute) or 1 (prismatic), got {}", where(source, node["sigma"]), sigma));
        }
        row.type = sigma == 1 ? JointType::Prismatic : JointType::Revolute;
        if (row.type == JointType::Prismatic && !has_limits) {
            throw InputError(fmt::format("{}: prismatic {} needs 'limits: [lower, upper]' in m", where(source, node), what));
        }
        row.alpha = node["alpha"] ? number(source, node["alpha"], "alpha") : 0.0;
        row.d = node["d"] ? number(source, node["d"], "d") : 0.0;
        row.theta = node["theta"] ? number(source, node["theta"], "theta") : 0.0;
        row.r = node["r"] ? number(source, node["r"], "r") : 0.0;
        // Khalil's a(j): 0 is the base, k is joint k; default: the previous joint (a serial chain).
        int antecedent = j;
        if (node["antecedent"]) {
            antecedent = integer(source, node["antecedent"], "antecedent");
            if (antecedent < 0 || antecedent > j) {
                throw InputError(fmt::format("{}: 'antecedent' of joint {} must be 0 (base) to {} (an earlier joint), got {}",
                                             where(source, node["antecedent"]), j + 1, j, antecedent));
            }
        }
        row.antecedent = antecedent - 1;
        const ChainError e = check.add(to_chain_joint(row));
        if (e != ChainError::Ok) throw InputError(fmt::format("{}: {}: {}", where(source, node), what, to_string(e)));
        d.mdh.push_back(row);
        d.chain.push_back(to_chain_joint(row));
    }
}

std::string directory_of(const std::string& path) {
    const auto slash = path.rfind('/');
    return slash == std::string::npos ? std::string() : path.substr(0, slash + 1);
}

void parse_urdf(const std::string& source, const YAML::Node& root, RobotDescription& d) {
    if (!root["urdf"]) throw InputError(fmt::format("{}: model urdf needs 'urdf: <file.urdf>' (relative to this file)", source));
    const std::string file = text(source, root["urdf"], "urdf");
    // Absolute, so that to_yaml() (stored in simulation truth files) still finds it from elsewhere.
    std::error_code absolute_error;
    d.urdf = (!file.empty() && file[0] == '/') ? file : directory_of(source) + file;
    const auto absolute = std::filesystem::absolute(d.urdf, absolute_error);
    if (!absolute_error) d.urdf = absolute.lexically_normal().string();
    // Regular files only: a description must not make the tool read a device or a pipe forever.
    std::error_code ec;
    if (!std::filesystem::is_regular_file(d.urdf, ec)) throw InputError(fmt::format("{}: URDF '{}' is not a readable file", where(source, root["urdf"]), d.urdf));
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
    }
    if (const YAML::Node joints = root["joints"]) {
        if (!joints.IsSequence() || static_cast<int>(joints.size()) != n) {
            throw InputError(fmt::format("{}: 'joints' must be a list of {} joints (the movable joints of {})", where(source, joints), n, d.urdf));
        }
        for (int j = 0; j < n; ++j) {
            const YAML::Node node = joints[static_cast<std::size_t>(j)];
            if (!node.IsMap()) throw InputError(fmt::format("{}: joint {} must be a map {{name, position, torque, limits}}", where(source, node), j + 1));
            check_keys(source, node, {"name", "position", "torque", "limits"}, fmt::format("joint {}", j + 1));
            bool has_limits = false;
            read_joint_columns(source, node, d.joints[static_cast<std::size_t>(j)], has_limits);
        }
    }
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
    YAML::Node root;
    try {
        root = YAML::Load(yaml_text);
    } catch (const YAML::Exception& e) {
        throw InputError(fmt::format("{}:{}:{}: invalid YAML: {}", source, e.mark.line + 1, e.mark.column + 1, e.msg));
    }
    if (!root.IsMap()) throw InputError(fmt::format("{}: expected a YAML map with at least 'model: planar2r'", source));
    check_keys(source, root, {"model", "L1", "joints", "friction", "rotor_inertia", "parameters", "gravity", "urdf"}, "the robot description");
    RobotDescription d;
    d.source = source;
    if (!root["model"]) throw InputError(fmt::format("{}: missing key 'model' (known models: {})", source, kKnownModels));
    d.model = text(source, root["model"], "model");
    if (d.model != "planar2r" && !is_serial(d.model)) {
        throw InputError(fmt::format("{}: unknown model '{}' (known models: {})", where(source, root["model"]), d.model, kKnownModels));
    }
    const auto only_for = [&](const char* key, bool allowed, const char* models) {
        if (root[key] && !allowed) throw InputError(fmt::format("{}: '{}' is only for model {}", where(source, root[key]), key, models));
    };
    only_for("L1", d.model == "planar2r", "planar2r");
    only_for("gravity", is_serial(d.model), "mdh or urdf");
    only_for("urdf", d.model == "urdf", "urdf");
    if (root["L1"]) {
        d.L1 = number(source, root["L1"], "L1");
        if (!(d.L1 > 0.0)) throw InputError(fmt::format("{}: 'L1' must be > 0 (link length in m)", where(source, root["L1"])));
    }
    if (d.model == "planar2r") parse_planar2r_joints(source, root["joints"], d);
    if (d.model == "mdh") parse_mdh_joints(source, root["joints"], d);
    if (d.model == "urdf") parse_urdf(source, root, d);
    if (const YAML::Node gravity = root["gravity"]) {
        if (!gravity.IsSequence() || gravity.size() != 3) throw InputError(fmt::format("{}: 'gravity' must be [gx, gy, gz] in m/s^2", where(source, gravity)));
        for (std::size_t k = 0; k < 3; ++k) d.gravity[static_cast<Eigen::Index>(k)] = number(source, gravity[k], "gravity");
    }
    if (const YAML::Node friction = root["friction"]) {
        if (!friction.IsMap()) throw InputError(fmt::format("{}: 'friction' must be a map", where(source, friction)));
        check_keys(source, friction, {"coulomb", "alpha", "offset"}, "friction");
        if (friction["coulomb"]) {
            const std::string c = text(source, friction["coulomb"], "coulomb");
            if (c == "sign") d.coulomb.model = CoulombModel::Sign;
            else if (c == "smooth") d.coulomb.model = CoulombModel::SmoothAtan;
            else throw InputError(fmt::format("{}: 'coulomb' must be sign or smooth, got '{}'", where(source, friction["coulomb"]), c));
        }
        if (friction["alpha"]) {
            d.coulomb.alpha = number(source, friction["alpha"], "alpha");
            if (!(d.coulomb.alpha > 0.0)) throw InputError(fmt::format("{}: 'alpha' must be > 0 (s/rad)", where(source, friction["alpha"])));
        }
        if (friction["offset"]) d.friction_offset = boolean(source, friction["offset"], "offset");
    }
    if (root["rotor_inertia"]) d.rotor_inertia = boolean(source, root["rotor_inertia"], "rotor_inertia");
    if (const YAML::Node parameters = root["parameters"]) {
        if (!parameters.IsMap()) throw InputError(fmt::format("{}: 'parameters' must be a map NAME: value", where(source, parameters)));
        // Serial robots take standard parameters (the base ones are derived); planar2r takes its base parameters.
        const std::vector<std::string> known =
            is_serial(d.model) ? standard_parameter_names(static_cast<int>(d.chain.size()), options_of(d)) : make_robot_model(d)->parameter_names();
        for (const auto& entry : parameters) {
            const std::string name = entry.first.as<std::string>();
            if (std::find(known.begin(), known.end(), name) == known.end()) {
                std::string list;
                for (const auto& n : known) list += (list.empty() ? "" : ", ") + n;
                throw InputError(fmt::format("{}: unknown parameter '{}' (this model has: {})", where(source, entry.first), name, list));
            }
            d.parameters.emplace_back(name, number(source, entry.second, name));
        }
    }
    return d;
}

RobotDescription load_robot_description(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw InputError(fmt::format("{}: cannot open robot description", path));
    std::ostringstream buffer;
    buffer << in.rdbuf();
    return parse_robot_description(buffer.str(), path);
}

std::unique_ptr<RobotModel> make_robot_model(const RobotDescription& d) {
    if (d.model == "planar2r") {
        Planar2RConfig config;
        config.L1 = d.L1;
        config.coulomb = d.coulomb;
        config.friction_offset = d.friction_offset;
        config.rotor_inertia = d.rotor_inertia;
        return std::make_unique<Planar2RModel>(config);
    }
    if (is_serial(d.model)) {
        SerialRobotConfig config;
        config.name = d.model;
        config.joints = d.chain;
        config.gravity = d.gravity;
        config.options = options_of(d);
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

Eigen::VectorXd true_parameters(const RobotDescription& d, const RobotModel& model) {
    if (const auto* serial = dynamic_cast<const SerialRobotModel*>(&model)) {
        Eigen::VectorXd standard = Eigen::VectorXd::Zero(serial->standard_parameter_count());
        for (const auto* list : {&d.model_parameters, &d.parameters}) {
            for (const auto& [name, value] : *list) {
                const int index = serial->standard_index(name);
                if (index < 0) throw InputError(fmt::format("{}: parameters: model {} has no standard parameter '{}'", d.source, model.model_name(), name));
                standard[index] = value;
            }
        }
        return serial->base_values(standard);
    }
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

// Written with yaml-cpp's emitter, not by hand: names, column names and paths are free text (a ':' or a
// '#' in a joint name must be quoted to read back), and the emitter knows YAML's quoting rules.
std::string to_yaml(const RobotDescription& d) {
    YAML::Emitter out;
    out.SetDoublePrecision(17);  // every double reads back bit for bit
    out << YAML::BeginMap;
    out << YAML::Key << "model" << YAML::Value << d.model;
    if (d.model == "planar2r") out << YAML::Key << "L1" << YAML::Value << d.L1;
    if (d.model == "urdf") out << YAML::Key << "urdf" << YAML::Value << d.urdf;
    if (is_serial(d.model)) {
        out << YAML::Key << "gravity" << YAML::Value << YAML::Flow << YAML::BeginSeq << d.gravity.x() << d.gravity.y() << d.gravity.z()
            << YAML::EndSeq;
    }
    out << YAML::Key << "joints" << YAML::Value << YAML::BeginSeq;
    for (std::size_t k = 0; k < d.joints.size(); ++k) {
        const auto& j = d.joints[k];
        out << YAML::Flow << YAML::BeginMap << YAML::Key << "name" << YAML::Value << j.name;
        if (d.model == "mdh") {
            const MdhJoint& m = d.mdh[k];
            out << YAML::Key << "sigma" << YAML::Value << (m.type == JointType::Prismatic ? 1 : 0);
            out << YAML::Key << "alpha" << YAML::Value << m.alpha << YAML::Key << "d" << YAML::Value << m.d;
            out << YAML::Key << "theta" << YAML::Value << m.theta << YAML::Key << "r" << YAML::Value << m.r;
            out << YAML::Key << "antecedent" << YAML::Value << m.antecedent + 1;
        }
        out << YAML::Key << "position" << YAML::Value << j.position_column << YAML::Key << "torque" << YAML::Value << j.torque_column;
        out << YAML::Key << "limits" << YAML::Value << YAML::Flow << YAML::BeginSeq << j.lower_limit << j.upper_limit << YAML::EndSeq;
        out << YAML::EndMap;
    }
    out << YAML::EndSeq;
    out << YAML::Key << "friction" << YAML::Value << YAML::BeginMap;
    out << YAML::Key << "coulomb" << YAML::Value << (d.coulomb.model == CoulombModel::Sign ? "sign" : "smooth");
    out << YAML::Key << "alpha" << YAML::Value << d.coulomb.alpha;
    out << YAML::Key << "offset" << YAML::Value << d.friction_offset << YAML::EndMap;
    out << YAML::Key << "rotor_inertia" << YAML::Value << d.rotor_inertia;
    if (!d.parameters.empty()) {
        out << YAML::Key << "parameters" << YAML::Value << YAML::BeginMap;
        for (const auto& [name, value] : d.parameters) out << YAML::Key << name << YAML::Value << value;
        out << YAML::EndMap;
    }
    out << YAML::EndMap;
    return std::string(out.c_str()) + "\n";
}

}  // namespace jacobid::robot
