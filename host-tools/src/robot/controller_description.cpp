// SPDX-License-Identifier: MIT
#include "robot/controller_description.hpp"

#include <fmt/core.h>
#include <yaml-cpp/yaml.h>

#include "core/errors.hpp"
#include "jacobid/yaml/yaml_section.hpp"

namespace jacobid::robot {
namespace {
using Section = yaml::YamlSection<InputError>;

std::vector<double> gains(Section& s, const char* key, std::size_t joints, const char* unit) {
    const YAML::Node list = s.list(key, joints, joints, fmt::format("numbers >= 0 ({}), one per joint", unit));
    std::vector<double> v;
    for (std::size_t j = 0; j < joints; ++j) {
        v.push_back(s.number_element(list[j], key, unit));
        if (!(v.back() >= 0.0)) s.fail(list[j], key, fmt::format("gain {} must be >= 0", v.back()));
    }
    return v;
}

}  // namespace

ControllerDescription parse_controller(const std::string& source, const YAML::Node& node, std::size_t joints) {
    Section s(source, node, "controller");
    if (!node.IsMap()) s.fail(node, "", "expected a map {kp: [...], kd: [...], rate: Hz} or {omega: rad/s, damping: zeta, rate: Hz}");
    ControllerDescription c;
    const bool explicit_gains = s.has("kp") || s.has("kd");
    if (explicit_gains && s.has("omega")) s.fail("omega", "give either kp and kd or omega (with damping), not both");
    if (explicit_gains) {
        if (!s.has("kp")) s.fail(node, "kp", "missing: kd needs kp");
        if (!s.has("kd")) s.fail(node, "kd", "missing: kp needs kd");
        if (s.has("damping")) s.fail("damping", "is only for omega (kp and kd are given)");
        c.kp = gains(s, "kp", joints, "N.m/rad");
        c.kd = gains(s, "kd", joints, "N.m s/rad");
    } else {
        if (!s.has("omega")) s.fail(node, "omega", "missing: give kp and kd (one per joint) or omega (rad/s)");
        c.omega = s.positive("omega", c.omega, "rad/s");
        c.damping = s.positive("damping", c.damping);
    }
    s.mark_used("kp");
    s.mark_used("kd");
    s.mark_used("omega");
    s.mark_used("damping");
    c.rate = s.positive("rate", c.rate, "Hz");
    c.substeps = static_cast<int>(s.integer("substeps", c.substeps, 1, 1000));
    s.reject_unknown();
    return c;
}

void write_controller(YAML::Emitter& out, const ControllerDescription& c) {
    out << YAML::Key << "controller" << YAML::Value << YAML::Flow << YAML::BeginMap;
    if (!c.kp.empty()) {
        out << YAML::Key << "kp" << YAML::Value << YAML::Flow << c.kp;
        out << YAML::Key << "kd" << YAML::Value << YAML::Flow << c.kd;
    } else {
        out << YAML::Key << "omega" << YAML::Value << c.omega << YAML::Key << "damping" << YAML::Value << c.damping;
    }
    out << YAML::Key << "rate" << YAML::Value << c.rate << YAML::Key << "substeps" << YAML::Value << c.substeps << YAML::EndMap;
}

}  // namespace jacobid::robot
