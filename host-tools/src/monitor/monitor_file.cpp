// SPDX-License-Identifier: MIT
#include "monitor/monitor_file.hpp"

#include <fmt/core.h>
#include <yaml-cpp/yaml.h>

#include "core/errors.hpp"
#include "jacobid/yaml/input_file.hpp"
#include "jacobid/yaml/yaml_section.hpp"

namespace jacobid::monitor {
namespace {
using Section = yaml::YamlSection<InputError>;

double non_negative(Section& s, const YAML::Node& n, const std::string& key, const std::string& unit) {
    const double v = s.number_element(n, key, unit);
    if (!(v >= 0.0)) s.fail(n, key, unit.empty() ? fmt::format("must be >= 0, got {}", v) : fmt::format("must be >= 0 ({}), got {}", unit, v));
    return v;
}

// `key`: one number >= 0 for every joint, or a list of one per joint.
std::vector<double> one_or_per_joint(Section& s, const std::string& key, const std::string& unit, std::size_t joints) {
    const YAML::Node n = s.get(key);
    std::vector<double> values;
    if (!n.IsSequence()) return {non_negative(s, n, key, unit)};
    if (n.size() != joints) s.fail(key, fmt::format("must be one number or a list of {} (one per joint)", joints));
    for (const auto& v : n) values.push_back(non_negative(s, v, key, unit));
    return values;
}

}  // namespace

const char* to_string(Estimator e) { return e == Estimator::Observer ? "observer" : "residual"; }

MonitorFile parse_monitor_file(const std::string& text, const std::string& source, std::size_t joints) {
    const YAML::Node root = yaml::load<InputError>(text, source);
    Section s(source, root, "");
    MonitorFile f;
    f.robot = s.text("robot", "");
    if (s.has("estimator")) {
        Section e = s.child("estimator");
        const std::string type = e.text("type", "observer");
        if (type != "observer" && type != "residual") e.fail("type", fmt::format("expected observer or residual, got '{}'", type));
        f.estimator.estimator = type == "observer" ? Estimator::Observer : Estimator::Residual;
        f.estimator.gain = e.positive("gain", f.estimator.gain, "1/s");
        f.estimator.velocity_window = e.positive("velocity_window", f.estimator.velocity_window, "s");
        f.estimator.acceleration_window = e.positive("acceleration_window", f.estimator.acceleration_window, "s");
        f.estimator.measured_velocity = e.boolean("measured_velocity", f.estimator.measured_velocity);
        f.estimator.xi = e.number("xi", f.estimator.xi);
        if (!(f.estimator.xi >= -1.0 && f.estimator.xi <= 1.0)) e.fail("xi", "must be in [-1, 1]");
        e.reject_unknown();
    }
    if (s.has("standing_velocity")) f.standing_velocity = one_or_per_joint(s, "standing_velocity", "rad/s", joints);
    f.standing_time = s.number("standing_time", f.standing_time, "s");
    if (!(f.standing_time >= 0.0)) s.fail("standing_time", "must be >= 0 s");
    if (s.has("band_margin")) f.band_margin = one_or_per_joint(s, "band_margin", "", joints);
    f.false_alarm_rate = s.number("false_alarm_rate", f.false_alarm_rate);
    if (!(f.false_alarm_rate >= 0.0 && f.false_alarm_rate < 1.0)) s.fail("false_alarm_rate", "must be in [0, 1) (per sample)");
    f.margin = s.number("margin", f.margin);
    if (!(f.margin >= 0.0)) s.fail("margin", "must be >= 0");
    f.hold = s.number("hold", f.hold, "s");
    if (!(f.hold >= 0.0)) s.fail("hold", "must be >= 0 s");
    f.confirm = static_cast<int>(s.integer("confirm", f.confirm, 1, 1000));
    const YAML::Node list = s.list("joints", joints, joints, "maps {moving: N.m, standing: N.m}, one per joint of the robot");
    for (std::size_t j = 0; j < joints; ++j) {
        Section js(source, list[j], fmt::format("joints[{}]", j));
        if (!js.has("moving")) js.fail(list[j], "moving", "missing (required)");
        if (!js.has("standing")) js.fail(list[j], "standing", "missing (required)");
        robot::JointThresholds t;
        t.moving = non_negative(js, js.get("moving"), "moving", "N.m");
        t.standing = non_negative(js, js.get("standing"), "standing", "N.m");
        js.reject_unknown();
        f.thresholds.push_back(t);
    }
    if (s.has("calibrated_from")) {
        const YAML::Node n = s.list("calibrated_from", 0, 100000, "file names");
        for (const auto& v : n) f.calibrated_from.push_back(s.element<std::string>(v, "calibrated_from", "a file name"));
    }
    s.mark_used("calibrated_from");
    s.reject_unknown();
    return f;
}

MonitorFile load_monitor_file(const std::string& path, std::size_t joints) {
    return parse_monitor_file(yaml::read_input_file<InputError>(path, "--monitor file"), path, joints);
}

std::string to_yaml(const MonitorFile& f) {
    YAML::Emitter out;
    out.SetDoublePrecision(6);
    out << YAML::BeginMap;
    out << YAML::Key << "robot" << YAML::Value << f.robot;
    out << YAML::Key << "estimator" << YAML::Value << YAML::Flow << YAML::BeginMap;
    out << YAML::Key << "type" << YAML::Value << to_string(f.estimator.estimator);
    out << YAML::Key << "gain" << YAML::Value << f.estimator.gain;
    out << YAML::Key << "velocity_window" << YAML::Value << f.estimator.velocity_window;
    out << YAML::Key << "acceleration_window" << YAML::Value << f.estimator.acceleration_window;
    out << YAML::Key << "measured_velocity" << YAML::Value << f.estimator.measured_velocity;
    out << YAML::Key << "xi" << YAML::Value << f.estimator.xi;
    out << YAML::EndMap;
    out << YAML::Key << "standing_velocity" << YAML::Value;
    if (f.standing_velocity.size() == 1) {
        out << f.standing_velocity.front();
    } else {
        out << YAML::Flow << f.standing_velocity;
    }
    out << YAML::Key << "standing_time" << YAML::Value << f.standing_time;
    out << YAML::Key << "band_margin" << YAML::Value;
    if (f.band_margin.size() == 1) {
        out << f.band_margin.front();
    } else {
        out << YAML::Flow << f.band_margin;
    }
    out << YAML::Key << "false_alarm_rate" << YAML::Value << f.false_alarm_rate;
    out << YAML::Key << "margin" << YAML::Value << f.margin;
    out << YAML::Key << "hold" << YAML::Value << f.hold;
    out << YAML::Key << "confirm" << YAML::Value << f.confirm;
    out << YAML::Key << "joints" << YAML::Value << YAML::BeginSeq;
    for (const auto& t : f.thresholds) {
        out << YAML::Flow << YAML::BeginMap << YAML::Key << "moving" << YAML::Value << t.moving << YAML::Key << "standing" << YAML::Value
            << t.standing << YAML::EndMap;
    }
    out << YAML::EndSeq;
    out << YAML::Key << "calibrated_from" << YAML::Value << YAML::Flow << f.calibrated_from;
    out << YAML::EndMap;
    return std::string("# jacobid monitor thresholds (docs/monitor.md): N.m, moving and beyond the Coulomb band when standing\n") + out.c_str() + "\n";
}

}  // namespace jacobid::monitor
