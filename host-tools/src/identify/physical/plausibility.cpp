// SPDX-License-Identifier: MIT
#include "identify/physical/plausibility.hpp"

#include <fmt/core.h>

#include <array>
#include <cctype>
#include <cmath>
#include <map>

#include "robot/load_friction_model.hpp"
#include "robot/presliding_model.hpp"
#include "robot/serial_robot_model.hpp"

namespace jacobid::identify {
namespace {

// A standard parameter name "ZZ3", "M2", "FOFF1" split into its kind and link.
struct StandardTerm {
    std::string kind;
    int link = 0;
};

StandardTerm split(const std::string& name) {
    std::size_t k = 0;
    while (k < name.size() && std::isalpha(static_cast<unsigned char>(name[k]))) ++k;
    StandardTerm t;
    t.kind = name.substr(0, k);
    t.link = k < name.size() ? std::atoi(name.c_str() + k) : 0;
    return t;
}

const char* why_of(const std::string& kind) {
    if (kind == "M") return "a mass";
    if (kind == "IA") return "a rotor inertia";
    if (kind == "FV") return "a viscous friction coefficient";
    if (kind == "FC") return "a Coulomb friction coefficient";
    return "an inertia (sum of diagonal inertias and masses)";
}

bool non_negative_kind(const std::string& kind) {
    return kind == "M" || kind == "IA" || kind == "FV" || kind == "FC" || kind == "XX" || kind == "YY" || kind == "ZZ";
}

// Coefficients of one link's terms in a base combination.
struct LinkTerms {
    std::map<std::string, double> c;
    double at(const std::string& kind) const {
        const auto it = c.find(kind);
        return it == c.end() ? 0.0 : it->second;
    }
};

// The combination sum_k c_k s_k is >= 0 for every physical robot (header comment). `why` names the
// dominant kind for the message.
bool provably_non_negative(const std::vector<std::pair<std::string, double>>& terms, std::string& why) {
    std::map<int, LinkTerms> links;
    std::string first_kind;
    for (const auto& [name, c] : terms) {
        const StandardTerm t = split(name);
        if (first_kind.empty()) first_kind = t.kind;
        links[t.link].c[t.kind] += c;
    }
    if (terms.empty()) return false;
    for (const auto& [link, lt] : links) {
        for (const auto& [kind, c] : lt.c) {
            if (non_negative_kind(kind)) {
                if (c < 0.0) return false;
                continue;
            }
            // First moments: b^2 <= 4 a c with a the inertias that contain the moment's axis squared.
            const bool moment = kind == "MX" || kind == "MY" || kind == "MZ";
            if (!moment) return false;  // products of inertia, friction offsets
            const double a = kind == "MX" ? lt.at("YY") + lt.at("ZZ") : kind == "MY" ? lt.at("XX") + lt.at("ZZ") : lt.at("XX") + lt.at("YY");
            const double m = lt.at("M");
            if (!(c * c <= 4.0 * a * m * (1.0 + 1e-9))) return false;
        }
    }
    why = why_of(first_kind);
    return true;
}

}  // namespace

std::vector<SignConstraint> sign_constraints(const robot::RobotModel& model) {
    if (const auto* presliding = dynamic_cast<const robot::PreslidingModel*>(&model)) {
        // The rigid-body model's constraints, then every presliding level FDj >= 0.
        std::vector<SignConstraint> out = sign_constraints(presliding->nominal());
        for (int j = 0; j < presliding->joint_count(); ++j) out.push_back({presliding->first_presliding_column() + j, "a presliding friction level"});
        return out;
    }
    // The rigid-body model's constraints; a load-dependent level FCLj may take either sign.
    if (const auto* loaded = dynamic_cast<const robot::LoadFrictionModel*>(&model)) return sign_constraints(loaded->nominal());
    std::vector<SignConstraint> out;
    const auto& names = model.parameter_names();
    if (const auto* serial = dynamic_cast<const robot::SerialRobotModel*>(&model)) {
        const auto& regrouping = serial->base().regrouping;
        const auto& standard = serial->standard_names();
        for (int b = 0; b < model.parameter_count(); ++b) {
            std::vector<std::pair<std::string, double>> terms;
            for (int s = 0; s < regrouping.cols(); ++s) {
                if (regrouping(b, s) != 0.0) terms.emplace_back(standard[static_cast<std::size_t>(s)], regrouping(b, s));
            }
            std::string why;
            if (provably_non_negative(terms, why)) out.push_back({b, why});
        }
        return out;
    }
    // Closed-form models (planar 2R): base parameters named after their leading standard parameter, with
    // non-negative regroupings (ZZ1R = ZZ1 + IA1 + M2 L1^2, docs/method.md "The planar 2R robot").
    for (int b = 0; b < model.parameter_count(); ++b) {
        std::string kind = split(names[static_cast<std::size_t>(b)]).kind;
        if (!kind.empty() && kind.back() == 'R' && kind != "R") kind.pop_back();
        if (non_negative_kind(kind)) out.push_back({b, why_of(kind)});
    }
    return out;
}

std::vector<PlausibilityViolation> plausibility_violations(const std::vector<SignConstraint>& constraints, const LsSolution& s) {
    std::vector<PlausibilityViolation> out;
    for (const auto& c : constraints) {
        const auto p = static_cast<std::size_t>(c.parameter);
        if (p >= s.identified.size() || !s.identified[p]) continue;
        const double x = s.x[c.parameter];
        if (x < 0.0) out.push_back({s.names[p], x, s.std_dev[c.parameter], s.rel_std_percent[c.parameter], c.why});
    }
    return out;
}

std::string describe(const PlausibilityViolation& v) {
    return fmt::format("{} = {:.4g} (2 sigma {:.3g}, %sigma_r {:.3g}) is negative, but it is {}: physically impossible{}", v.name, v.value,
                       2.0 * v.std_dev, v.rel_std_percent, v.why,
                       v.value + 2.0 * v.std_dev >= 0.0 ? " (within 2 sigma of 0: poorly excited)" : " (more than 2 sigma below 0: a model or data problem)");
}

}  // namespace jacobid::identify
