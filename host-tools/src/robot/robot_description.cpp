#include "robot/robot_description.hpp"

#include <fmt/core.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include "cli/command.hpp"
#include "robot/planar2r_model.hpp"

namespace jacobid::robot {
namespace {

using cli::InputError;

std::string where(const std::string& source, const YAML::Node& node) {
    const YAML::Mark m = node.Mark();
    if (m.is_null()) return source;
    return fmt::format("{}:{}:{}", source, m.line + 1, m.column + 1);
}

double number(const std::string& source, const YAML::Node& node, const std::string& key) {
    try {
        const double v = node.as<double>();
        if (!std::isfinite(v)) throw YAML::Exception(node.Mark(), "not finite");
        return v;
    } catch (const YAML::Exception&) {
        throw InputError(fmt::format("{}: '{}' must be a finite number", where(source, node), key));
    }
}

bool boolean(const std::string& source, const YAML::Node& node, const std::string& key) {
    try {
        return node.as<bool>();
    } catch (const YAML::Exception&) {
        throw InputError(fmt::format("{}: '{}' must be true or false", where(source, node), key));
    }
}

std::string text(const std::string& source, const YAML::Node& node, const std::string& key) {
    if (!node.IsScalar()) throw InputError(fmt::format("{}: '{}' must be a string", where(source, node), key));
    return node.as<std::string>();
}

void check_keys(const std::string& source, const YAML::Node& map, const std::set<std::string>& known, const std::string& what) {
    for (const auto& entry : map) {
        const std::string key = entry.first.as<std::string>();
        if (!known.count(key)) {
            std::string list;
            for (const auto& k : known) list += (list.empty() ? "" : ", ") + k;
            throw InputError(fmt::format("{}: unknown key '{}' in {} (known: {})", where(source, entry.first), key, what, list));
        }
    }
}

std::vector<JointDescription> default_joints(int count) {
    std::vector<JointDescription> joints;
    for (int j = 1; j <= count; ++j) joints.push_back({fmt::format("j{}", j), fmt::format("q{}", j), fmt::format("tau{}", j), -2.5, 2.5});
    return joints;
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
    check_keys(source, root, {"model", "L1", "joints", "friction", "rotor_inertia", "parameters"}, "the robot description");
    RobotDescription d;
    d.source = source;
    if (!root["model"]) throw InputError(fmt::format("{}: missing key 'model' (known models: planar2r)", source));
    d.model = text(source, root["model"], "model");
    if (d.model != "planar2r") {
        throw InputError(fmt::format("{}: unknown model '{}' (known models: planar2r)", where(source, root["model"]), d.model));
    }
    const int joint_count = 2;
    if (root["L1"]) {
        d.L1 = number(source, root["L1"], "L1");
        if (!(d.L1 > 0.0)) throw InputError(fmt::format("{}: 'L1' must be > 0 (link length in m)", where(source, root["L1"])));
    }
    d.joints = default_joints(joint_count);
    if (const YAML::Node joints = root["joints"]) {
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
            if (node["name"]) joint.name = text(source, node["name"], "name");
            if (node["position"]) joint.position_column = text(source, node["position"], "position");
            if (node["torque"]) joint.torque_column = text(source, node["torque"], "torque");
            if (const YAML::Node limits = node["limits"]) {
                if (!limits.IsSequence() || limits.size() != 2) {
                    throw InputError(fmt::format("{}: 'limits' must be [lower, upper] in rad", where(source, limits)));
                }
                joint.lower_limit = number(source, limits[0], "limits");
                joint.upper_limit = number(source, limits[1], "limits");
                if (joint.lower_limit > joint.upper_limit) {
                    throw InputError(fmt::format("{}: 'limits' lower {} > upper {}", where(source, limits), joint.lower_limit, joint.upper_limit));
                }
            }
        }
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
        const auto model = make_robot_model(d);
        for (const auto& entry : parameters) {
            const std::string name = entry.first.as<std::string>();
            if (model->parameter_index(name) < 0) {
                std::string list;
                for (const auto& n : model->parameter_names()) list += (list.empty() ? "" : ", ") + n;
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
    throw InputError(fmt::format("{}: unknown model '{}' (known models: planar2r)", d.source, d.model));
}

Eigen::VectorXd true_parameters(const RobotDescription& d, const RobotModel& model) {
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

std::string to_yaml(const RobotDescription& d) {
    std::string s = fmt::format("model: {}\nL1: {}\njoints:\n", d.model, d.L1);
    for (const auto& j : d.joints) {
        s += fmt::format("  - {{name: {}, position: {}, torque: {}, limits: [{}, {}]}}\n", j.name, j.position_column, j.torque_column,
                         j.lower_limit, j.upper_limit);
    }
    s += fmt::format("friction:\n  coulomb: {}\n  alpha: {}\n  offset: {}\n", d.coulomb.model == CoulombModel::Sign ? "sign" : "smooth",
                     d.coulomb.alpha, d.friction_offset ? "true" : "false");
    s += fmt::format("rotor_inertia: {}\n", d.rotor_inertia ? "true" : "false");
    if (!d.parameters.empty()) {
        s += "parameters:\n";
        for (const auto& [name, value] : d.parameters) s += fmt::format("  {}: {:.17g}\n", name, value);
    }
    return s;
}

}  // namespace jacobid::robot
