// SPDX-License-Identifier: MIT
#include "sim/effect_spec.hpp"

#include <fast_float/fast_float.h>
#include <fmt/core.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <algorithm>
#include <fstream>
#include <map>
#include <sstream>

#include "core/errors.hpp"
#include "jacobid/yaml/input_file.hpp"

namespace jacobid::sim {
namespace {

// Keys each effect accepts, the first being the magnitude.
std::vector<std::string> allowed_keys(EffectKind kind) {
    switch (kind) {
        case EffectKind::Stribeck: return {"joint", "value", "velocity"};
        case EffectKind::Cogging: return {"joint", "amplitude", "value", "order", "phase"};
        case EffectKind::Gravity: return {"tilt", "direction", "mx1"};
        case EffectKind::TorqueDelay: return {"value"};
        case EffectKind::Presliding: return {"joint", "value", "displacement"};
        case EffectKind::CoulombSmoothing: return {"joint", "value", "alpha"};
        default: return {"joint", "value"};
    }
}

std::string join(const std::vector<std::string>& v) {
    std::string s;
    for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
    return s;
}

}  // namespace

double number_or_throw(const std::string& text, const std::string& where) {
    double v = 0.0;
    const auto r = fast_float::from_chars(text.data(), text.data() + text.size(), v);
    if (r.ec != std::errc() || r.ptr != text.data() + text.size() || !std::isfinite(v)) {
        throw InputError(fmt::format("{}: '{}' is not a finite number", where, text));
    }
    return v;
}

namespace {

// Builds a spec from key/value text pairs; `where(key)` names the place of a key in errors.
template <class Where>
EffectSpec build(const std::string& name, const std::vector<std::pair<std::string, std::string>>& pairs, int joints, Where where) {
    const auto kind = effect_kind(name);
    if (!kind) {
        std::vector<std::string> names;
        for (EffectKind k : kAllEffects) names.emplace_back(effect_name(k));
        throw InputError(fmt::format("{}: unknown effect '{}' (expected one of {})", where(""), name, join(names)));
    }
    EffectSpec s;
    s.kind = *kind;
    const auto keys = allowed_keys(s.kind);
    std::map<std::string, double> given;
    for (const auto& [key, text] : pairs) {
        if (std::find(keys.begin(), keys.end(), key) == keys.end()) {
            throw InputError(fmt::format("{}: unknown key '{}' for {} (expected {})", where(key), key, name, join(keys)));
        }
        if (given.count(key)) throw InputError(fmt::format("{}: key '{}' given twice", where(key), key));
        given[key] = number_or_throw(text, where(key));
        // Far beyond any real effect (1e6 N.m, kg.m^2, kg.m, rad/s): 1e300 made the simulated robot's mass
        // matrix indefinite or its torques overflow, and the error named no effect.
        constexpr double kMaxEffectValue = 1e6;
        if (key != "joint" && key != "order" && !(std::abs(given[key]) <= kMaxEffectValue)) {
            throw InputError(fmt::format("{}: {} must be within +-{:g}", where(key), given[key], kMaxEffectValue));
        }
    }
    auto need = [&](const char* key) {
        if (!given.count(key)) throw InputError(fmt::format("{}: {} needs '{}'", where(""), name, key));
        return given[key];
    };
    if (effect_has_joint(s.kind)) {
        const double j = need("joint");
        if (j != std::floor(j) || j < 1 || j > joints) {
            throw InputError(fmt::format("{}: joint {} out of range (expected an integer 1..{})", where("joint"), j, joints));
        }
        s.joint = static_cast<int>(j) - 1;
    }
    switch (s.kind) {
        case EffectKind::Cogging: {
            if (given.count("amplitude") && given.count("value")) throw InputError(fmt::format("{}: give amplitude or value, not both", where("value")));
            s.value = given.count("amplitude") ? given["amplitude"] : need("value");
            if (given.count("order")) {
                const double k = given["order"];
                if (k != std::floor(k) || k < 1 || k > 1000) throw InputError(fmt::format("{}: order must be an integer 1..1000", where("order")));
                s.order = static_cast<int>(k);
            }
            if (given.count("phase")) s.phase = given["phase"];
            break;
        }
        case EffectKind::Gravity: {
            s.tilt = need("tilt");
            if (!(std::abs(s.tilt) <= 90.0)) throw InputError(fmt::format("{}: tilt must be within [-90, 90] degrees", where("tilt")));
            if (given.count("direction")) s.direction = given["direction"];
            if (given.count("mx1")) s.mx1 = given["mx1"];
            s.value = kGravity * std::sin(std::abs(s.tilt) * M_PI / 180.0) * std::abs(s.mx1);
            break;
        }
        case EffectKind::Stribeck:
            s.value = need("value");
            if (given.count("velocity")) s.velocity = given["velocity"];
            if (!(s.velocity > 0.0)) throw InputError(fmt::format("{}: velocity must be > 0 rad/s", where("velocity")));
            break;
        case EffectKind::CoulombSmoothing:
            s.value = need("value");
            if (given.count("alpha")) s.alpha = given["alpha"];
            if (!(s.alpha > 0.0)) throw InputError(fmt::format("{}: alpha must be > 0 s/rad", where("alpha")));
            break;
        case EffectKind::Presliding:
            s.value = need("value");
            if (given.count("displacement")) s.displacement = given["displacement"];
            if (!(s.displacement > 0.0 && s.displacement <= 1.0)) {
                throw InputError(fmt::format("{}: displacement must be within (0, 1] rad", where("displacement")));
            }
            break;
        case EffectKind::TorqueDelay:
            s.value = need("value");
            if (!(s.value >= 0.0 && s.value <= 1.0)) throw InputError(fmt::format("{}: delay must be within [0, 1] s", where("value")));
            break;
        case EffectKind::RotorInertia:
            s.value = need("value");
            if (!(s.value >= 0.0)) throw InputError(fmt::format("{}: a rotor inertia must be >= 0 kg.m^2, got {}", where("value"), s.value));
            break;
        default: s.value = need("value"); break;
    }
    return s;
}

}  // namespace

EffectToken split_effect_token(const std::string& token) {
    EffectToken t;
    t.where = fmt::format("--effect '{}'", token);
    const auto colon = token.find(':');
    t.name = token.substr(0, colon);
    if (colon != std::string::npos) {
        const std::string rest = token.substr(colon + 1);
        std::size_t start = 0;
        while (start <= rest.size()) {
            const auto comma = rest.find(',', start);
            const std::string item = rest.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
            const auto eq = item.find('=');
            if (eq == std::string::npos || eq == 0) {
                throw InputError(fmt::format("{}: '{}' is not key=value", t.where, item));
            }
            t.pairs.emplace_back(item.substr(0, eq), item.substr(eq + 1));
            if (comma == std::string::npos) break;
            start = comma + 1;
        }
    }
    return t;
}

EffectSpec parse_effect(const std::string& token, int joints) {
    const EffectToken t = split_effect_token(token);
    return build(t.name, t.pairs, joints, [&](const std::string& key) { return key.empty() ? t.where : t.where + " key '" + key + "'"; });
}

std::vector<EffectSpec> parse_effects_yaml(const std::string& text, const std::string& source, int joints) {
    YAML::Node root;
    try {
        root = YAML::Load(text);
    } catch (const YAML::Exception& e) {
        throw InputError(fmt::format("{}:{}:{}: invalid YAML: {}", source, e.mark.line + 1, e.mark.column + 1, e.msg));
    }
    auto at = [&](const YAML::Node& n) { return fmt::format("{}:{}:{}", source, n.Mark().line + 1, n.Mark().column + 1); };
    if (!root.IsMap() || !root["effects"] || !root["effects"].IsSequence()) {
        throw InputError(fmt::format("{}:1:1: expected a map with a list 'effects'", source));
    }
    std::vector<EffectSpec> specs;
    for (const YAML::Node& item : root["effects"]) {
        if (!item.IsMap() || !item["name"]) throw InputError(fmt::format("{}: each effect needs a map with 'name'", at(item)));
        std::vector<std::pair<std::string, std::string>> pairs;
        std::map<std::string, YAML::Node> nodes;
        for (const auto& kv : item) {
            const std::string key = kv.first.as<std::string>();
            if (key == "name") continue;
            if (!kv.second.IsScalar()) throw InputError(fmt::format("{}: '{}' must be a number", at(kv.second), key));
            pairs.emplace_back(key, kv.second.as<std::string>());
            nodes[key] = kv.second;
        }
        specs.push_back(build(item["name"].as<std::string>(), pairs, joints, [&](const std::string& key) {
            return key.empty() || !nodes.count(key) ? at(item) : fmt::format("{} key '{}'", at(nodes[key]), key);
        }));
    }
    return specs;
}

std::vector<EffectSpec> load_effects_file(const std::string& path, int joints) {
    return parse_effects_yaml(yaml::read_input_file<InputError>(path, "--effects file"), path, joints);
}

EffectTerm term_of(const EffectSpec& spec) { return {spec.kind, spec.joint, spec.velocity, spec.order, spec.displacement, spec.alpha}; }

Eigen::VectorXd injected_coefficients(const EffectSpec& spec, const robot::RobotModel& nominal, const Eigen::VectorXd& x) {
    switch (spec.kind) {
        case EffectKind::Cogging: {
            const double phase = spec.phase * M_PI / 180.0;
            // amplitude sin(k q + phase) = amplitude cos(phase) sin(k q) + amplitude sin(phase) cos(k q)
            return Eigen::Vector2d(spec.value * std::cos(phase), spec.value * std::sin(phase));
        }
        case EffectKind::Gravity: {
            const double gp = kGravity * std::sin(spec.tilt * M_PI / 180.0);
            const double gx = gp * std::cos(spec.direction * M_PI / 180.0), gy = gp * std::sin(spec.direction * M_PI / 180.0);
            const int imx = nominal.parameter_index("MX2"), imy = nominal.parameter_index("MY2");
            const double mx2 = imx >= 0 ? x[imx] : 0.0, my2 = imy >= 0 ? x[imy] : 0.0;
            Eigen::VectorXd c(4);
            c << gx * spec.mx1, gy * spec.mx1, gx * mx2 + gy * my2, gy * mx2 - gx * my2;
            return c;
        }
        case EffectKind::TorqueDelay: return Eigen::VectorXd(0);
        default: return Eigen::VectorXd::Constant(1, spec.value);
    }
}

nlohmann::json to_json(const EffectSpec& s) {
    nlohmann::json j;
    j["name"] = effect_name(s.kind);
    j["joint"] = s.joint >= 0 ? nlohmann::json(s.joint + 1) : nlohmann::json(nullptr);
    j["value"] = s.value;
    j["unit"] = effect_unit(s.kind);
    if (s.kind == EffectKind::Stribeck) j["velocity"] = s.velocity;
    if (s.kind == EffectKind::Presliding) j["displacement"] = s.displacement;
    if (s.kind == EffectKind::CoulombSmoothing) j["alpha"] = s.alpha;
    if (s.kind == EffectKind::Cogging) {
        j["order"] = s.order;
        j["phase"] = s.phase;
    }
    if (s.kind == EffectKind::Gravity) {
        j["tilt"] = s.tilt;
        j["direction"] = s.direction;
        j["mx1"] = s.mx1;
    }
    return j;
}

}  // namespace jacobid::sim
