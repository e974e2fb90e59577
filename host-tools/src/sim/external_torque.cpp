// SPDX-License-Identifier: MIT
#include "sim/external_torque.hpp"

#include <fmt/core.h>

#include <cmath>
#include <map>

#include "core/errors.hpp"
#include "sim/effect_spec.hpp"

namespace jacobid::sim {
namespace {

constexpr const char* kShapes[] = {"pulse", "sine", "ramp"};

ContactShape shape_of(const std::string& text, const std::string& where) {
    for (int s = 0; s < 3; ++s) {
        if (text == kShapes[s]) return static_cast<ContactShape>(s);
    }
    throw InputError(fmt::format("{}: shape '{}' is not one of pulse, sine, ramp", where, text));
}

}  // namespace

bool is_external_torque(const std::string& token) { return token == "external" || token.rfind("external:", 0) == 0; }

ExternalTorque parse_external_torque(const std::string& token, int joints) {
    const EffectToken t = split_effect_token(token);
    auto where = [&](const std::string& key) { return t.where + " key '" + key + "'"; };
    std::map<std::string, double> given;
    ExternalTorque c;
    for (const auto& [key, text] : t.pairs) {
        if (key != "joint" && key != "start" && key != "duration" && key != "value" && key != "shape") {
            throw InputError(fmt::format("{}: unknown key '{}' for external (expected joint, start, duration, value, shape)", where(key), key));
        }
        if (given.count(key)) throw InputError(fmt::format("{}: key '{}' given twice", where(key), key));
        if (key == "shape") {
            c.shape = shape_of(text, where(key));
            given[key] = 0.0;
            continue;
        }
        given[key] = number_or_throw(text, where(key));
    }
    for (const char* key : {"joint", "start", "duration", "value"}) {
        if (!given.count(key)) throw InputError(fmt::format("{}: external needs '{}' (joint=J,start=S,duration=D,value=V)", t.where, key));
    }
    const double j = given["joint"];
    if (j != std::floor(j) || j < 1 || j > joints) throw InputError(fmt::format("{}: joint {} out of range (expected an integer 1..{})", where("joint"), j, joints));
    c.joint = static_cast<int>(j) - 1;
    c.start = given["start"];
    if (!(c.start >= 0.0)) throw InputError(fmt::format("{}: start {} s must be >= 0", where("start"), c.start));
    c.duration = given["duration"];
    if (!(c.duration > 0.0)) throw InputError(fmt::format("{}: duration {} s must be > 0", where("duration"), c.duration));
    c.value = given["value"];
    // As the other effects (effect_spec.cpp): beyond 1e6 N.m a torque only overflows the simulation.
    if (!(std::abs(c.value) <= 1e6)) throw InputError(fmt::format("{}: {} must be within +-1e6", where("value"), c.value));
    return c;
}

void external_torque_at(const std::vector<ExternalTorque>& contacts, double t, int joints, Eigen::VectorXd& out) {
    out.setZero(joints);
    for (const ExternalTorque& c : contacts) {
        const double s = (t - c.start) / c.duration;  // 0 .. 1 over the contact
        if (!(s >= 0.0 && s < 1.0)) continue;
        switch (c.shape) {
            case ContactShape::Pulse: out[c.joint] += c.value; break;
            case ContactShape::Sine: out[c.joint] += c.value * std::sin(M_PI * s); break;
            case ContactShape::Ramp: out[c.joint] += c.value * s; break;
        }
    }
}

nlohmann::json to_json(const ExternalTorque& c) {
    return {{"name", "external"},
            {"joint", c.joint + 1},
            {"start", c.start},
            {"duration", c.duration},
            {"value", c.value},
            {"shape", kShapes[static_cast<int>(c.shape)]}};
}

}  // namespace jacobid::sim
