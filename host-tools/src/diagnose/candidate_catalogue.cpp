// SPDX-License-Identifier: MIT
#include "diagnose/candidate_catalogue.hpp"

#include <algorithm>
#include <cmath>

namespace jacobid::diagnose {

Catalogue candidate_catalogue(const sim::EffectContext& context, const CatalogueSettings& settings) {
    using sim::EffectKind;
    Catalogue c;
    auto add = [&](sim::EffectTerm t) {
        std::string why;
        if (sim::term_applicable(t, context, &why)) {
            c.terms.push_back(t);
        } else if (std::find(c.notes.begin(), c.notes.end(), why) == c.notes.end()) {
            c.notes.push_back(why);
        }
    };
    for (int j = 0; j < context.joints; ++j) {
        add({EffectKind::CoulombOffset, j, 0.0, 0});
        add({EffectKind::CoulombAsymmetry, j, 0.0, 0});
        for (double vs : settings.stribeck_velocities) add({EffectKind::Stribeck, j, vs, 0});
        for (double xp : settings.presliding_displacements) add({EffectKind::Presliding, j, 0.0, 0, xp});
        const robot::CoulombSign& own = context.sign(j);
        for (double a : settings.coulomb_alphas) {
            const bool same = own.model == robot::CoulombModel::SmoothAtan && std::abs(a / own.alpha - 1.0) < 0.01;
            if (!same) add({EffectKind::CoulombSmoothing, j, 0.0, 0, 0.0, a});
        }
        if (context.load) add({EffectKind::CoulombLoad, j, 0.0, 0});
        add({EffectKind::ViscousNonlinear, j, 0.0, 0});
        for (int k = 2; k <= settings.max_cogging_order; ++k) add({EffectKind::Cogging, j, 0.0, k});
        add({EffectKind::RotorInertia, j, 0.0, 0});
    }
    add({EffectKind::Gravity, -1, 0.0, 0});
    return c;
}

}  // namespace jacobid::diagnose
