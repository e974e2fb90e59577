// SPDX-License-Identifier: MIT
#include "sim/effect_terms.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>

namespace jacobid::sim {
namespace {

struct KindInfo {
    EffectKind kind;
    const char* name;
    const char* unit;
};

constexpr KindInfo kKinds[] = {
    {EffectKind::CoulombOffset, "coulomb_offset", "N.m"},       {EffectKind::CoulombAsymmetry, "coulomb_asymmetry", "N.m"},
    {EffectKind::Stribeck, "stribeck", "N.m"},                  {EffectKind::ViscousNonlinear, "viscous_nonlinear", "N.m s^2/rad^2"},
    {EffectKind::Gravity, "gravity", "N.m"},                    {EffectKind::Cogging, "cogging", "N.m"},
    {EffectKind::RotorInertia, "rotor_inertia", "kg m^2"},      {EffectKind::TorqueDelay, "torque_delay", "s"},
    {EffectKind::Presliding, "presliding", "N.m"},             {EffectKind::CoulombSmoothing, "coulomb_smoothing", "N.m"},
    {EffectKind::CoulombLoad, "coulomb_load", "N.m/N.m"},
};

const KindInfo& info(EffectKind kind) {
    for (const auto& k : kKinds) {
        if (k.kind == kind) return k;
    }
    return kKinds[0];
}

}  // namespace

const char* effect_name(EffectKind kind) { return info(kind).name; }
const char* effect_unit(EffectKind kind) { return info(kind).unit; }

std::optional<EffectKind> effect_kind(const std::string& name) {
    for (const auto& k : kKinds) {
        if (name == k.name) return k.kind;
    }
    return std::nullopt;
}

bool effect_has_joint(EffectKind kind) { return kind != EffectKind::Gravity && kind != EffectKind::TorqueDelay; }

bool effect_has_history(EffectKind kind) { return kind == EffectKind::Presliding; }

int EffectTerm::column_count() const {
    switch (kind) {
        case EffectKind::Cogging: return 2;
        case EffectKind::Gravity: return 4;
        case EffectKind::TorqueDelay: return 0;
        default: return 1;
    }
}

bool EffectTerm::same_as(const EffectTerm& o) const {
    if (kind != o.kind || joint != o.joint) return false;
    // Only the hyper-parameter of this kind: the others are whatever their producer left in them.
    switch (kind) {
        case EffectKind::Stribeck: return velocity == o.velocity;
        case EffectKind::Cogging: return order == o.order;
        case EffectKind::Presliding: return displacement == o.displacement;
        case EffectKind::CoulombSmoothing: return alpha == o.alpha;
        default: return true;
    }
}

std::string EffectTerm::label() const {
    std::string s = effect_name(kind);
    if (joint >= 0) s += fmt::format(" j{}", joint + 1);
    if (kind == EffectKind::Stribeck) s += fmt::format(" vs={:g} rad/s", velocity);
    if (kind == EffectKind::Cogging) s += fmt::format(" k={}", order);
    if (kind == EffectKind::Presliding) s += fmt::format(" xp={:g} rad", displacement);
    if (kind == EffectKind::CoulombSmoothing) s += fmt::format(" alpha={:g} s/rad", alpha);
    return s;
}

std::vector<std::string> EffectTerm::column_names() const {
    const std::string base = fmt::format("{}{}", effect_name(kind), joint >= 0 ? std::to_string(joint + 1) : std::string());
    switch (kind) {
        case EffectKind::Stribeck: return {fmt::format("{}_vs{:g}", base, velocity)};
        case EffectKind::Presliding: return {fmt::format("{}_xp{:g}", base, displacement)};
        case EffectKind::CoulombSmoothing: return {fmt::format("{}_alpha{:g}", base, alpha)};
        case EffectKind::Cogging: return {fmt::format("{}_k{}_sin", base, order), fmt::format("{}_k{}_cos", base, order)};
        case EffectKind::Gravity: return {base + "_a1", base + "_b1", base + "_a2", base + "_b2"};
        case EffectKind::TorqueDelay: return {};
        default: return {base};
    }
}

bool term_applicable(const EffectTerm& term, const EffectContext& context, std::string* why_not) {
    if (term.kind == EffectKind::Gravity && context.model_name != "planar2r") {
        if (why_not) {
            *why_not = fmt::format("gravity: only modelled for planar2r (a tilted base); model '{}' has no planar gravity columns",
                                   context.model_name);
        }
        return false;
    }
    if (effect_has_joint(term.kind) && (term.joint < 0 || term.joint >= context.joints)) {
        if (why_not) *why_not = fmt::format("{}: joint {} out of range 1..{}", effect_name(term.kind), term.joint + 1, context.joints);
        return false;
    }
    if (term.kind == EffectKind::CoulombLoad) {
        const auto* loaded = context.load ? &context.load->loaded_joints() : nullptr;
        if (!loaded || std::find(loaded->begin(), loaded->end(), term.joint) == loaded->end()) {
            if (why_not) {
                *why_not = fmt::format("coulomb_load j{}: gravity never loads joint {} under the description's parameters (a vertical axis, "
                                       "a horizontal robot, or no inertial parameters)", term.joint + 1, term.joint + 1);
            }
            return false;
        }
    }
    return true;
}

void term_columns(const EffectTerm& term, const EffectContext& context, const double* q, const double* qd, const double* qdd,
                  Eigen::Ref<Eigen::MatrixXd> columns, const double* load_factors) {
    columns.setZero();
    const int j = term.joint;
    switch (term.kind) {
        case EffectKind::CoulombOffset: columns(j, 0) = 1.0; break;
        case EffectKind::CoulombAsymmetry: columns(j, 0) = std::abs(context.sign(j)(qd[j])); break;
        case EffectKind::Stribeck: {
            const double r = qd[j] / term.velocity;
            columns(j, 0) = context.sign(j)(qd[j]) * std::exp(-r * r);
            break;
        }
        case EffectKind::ViscousNonlinear: columns(j, 0) = qd[j] * std::abs(qd[j]); break;
        case EffectKind::Cogging:
            columns(j, 0) = std::sin(term.order * q[j]);
            columns(j, 1) = std::cos(term.order * q[j]);
            break;
        case EffectKind::RotorInertia: columns(j, 0) = qdd[j]; break;
        case EffectKind::Gravity: {
            const double s1 = std::sin(q[0]), c1 = std::cos(q[0]), s12 = std::sin(q[0] + q[1]), c12 = std::cos(q[0] + q[1]);
            columns(0, 0) = s1;
            columns(0, 1) = -c1;
            columns(0, 2) = s12;
            columns(1, 2) = s12;
            columns(0, 3) = -c12;
            columns(1, 3) = -c12;
            break;
        }
        case EffectKind::TorqueDelay: break;
        case EffectKind::Presliding: break;  // history column: AugmentedModel::history_columns
        case EffectKind::CoulombSmoothing: columns(j, 0) = robot::CoulombSign{robot::CoulombModel::SmoothAtan, term.alpha}(qd[j]); break;
        case EffectKind::CoulombLoad: {
            if (!load_factors) {
                thread_local std::vector<double> factors;  // regressors run on several threads at once
                factors.resize(static_cast<std::size_t>(context.joints));
                context.load->load_factors(q, factors.data());
                load_factors = factors.data();
            }
            columns(j, 0) = load_factors[j] * context.sign(j)(qd[j]);
            break;
        }
    }
}

double term_value(const EffectTerm& term, const Eigen::VectorXd& x) {
    if (term.kind == EffectKind::Cogging || term.kind == EffectKind::Gravity) return std::hypot(x[0], x[1]);
    return x.size() > 0 ? x[0] : 0.0;
}

double term_value_std(const EffectTerm& term, const Eigen::VectorXd& x, const Eigen::MatrixXd& cov) {
    if (term.kind == EffectKind::Cogging || term.kind == EffectKind::Gravity) {
        const double a = std::hypot(x[0], x[1]);
        if (!(a > 0.0)) return std::sqrt(0.5 * (cov(0, 0) + cov(1, 1)));
        Eigen::Vector2d g(x[0] / a, x[1] / a);
        return std::sqrt(std::max(0.0, double(g.transpose() * cov.topLeftCorner<2, 2>() * g)));
    }
    return cov.size() > 0 ? std::sqrt(std::max(0.0, cov(0, 0))) : 0.0;
}

}  // namespace jacobid::sim
