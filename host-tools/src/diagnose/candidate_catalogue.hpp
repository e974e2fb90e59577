// SPDX-License-Identifier: MIT
#pragma once
// The candidate effects the diagnosis tries, each with its hyper-parameter on a grid: Stribeck velocities
// (a geometric grid, 0.02-0.5 rad/s), presliding displacements (x_p of a Dahl state, a factor-2 grid
// 5e-5-3.2e-3 rad: the range identify's presliding_displacement auto searches), Coulomb smoothings (alpha'
// on a factor-2 grid 10-1280 s/rad, the description's own left out: a wrong alpha is named as such instead
// of being absorbed by Stribeck terms), cogging orders 2..max (order 1 on joint 1 is what a tilted base does,
// and the gravity candidate covers it), one term per joint for the others, gravity once. torque_delay has
// no columns: the selection searches it by shifting the torque channel.
#include <string>
#include <vector>

#include "sim/effect_terms.hpp"

namespace jacobid::diagnose {

struct CatalogueSettings {
    std::vector<double> stribeck_velocities{0.02, 0.025, 0.03, 0.04, 0.05, 0.06, 0.07, 0.08, 0.1, 0.12, 0.14, 0.17, 0.2, 0.25, 0.3, 0.4, 0.5};
    std::vector<double> presliding_displacements{5e-5, 1e-4, 2e-4, 4e-4, 8e-4, 1.6e-3, 3.2e-3};
    // Coulomb smoothing alphas other than the description's (a factor-2 grid, the range of friction alpha: auto).
    std::vector<double> coulomb_alphas{10, 20, 40, 80, 160, 320, 640, 1280};
    int max_cogging_order = 30;
    bool torque_delay = true;
};

struct Catalogue {
    std::vector<sim::EffectTerm> terms;
    std::vector<std::string> notes;  // effects that do not apply to this robot, and why
};

Catalogue candidate_catalogue(const sim::EffectContext& context, const CatalogueSettings& settings);

}  // namespace jacobid::diagnose
