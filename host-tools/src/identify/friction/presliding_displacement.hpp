// SPDX-License-Identifier: MIT
#pragma once
// `friction: {presliding: dahl, presliding_displacement: auto}`: each joint's presliding displacement x_p
// chosen from the identification log by blocked held-out error (docs/method.md, "Presliding friction
// (Dahl)"), the same procedure as the Coulomb smoothing (shape_selection.hpp): candidate columns FDj at every
// x_p, integrated along the log's positions through the play operator, never the validation log.
#include <string>
#include <vector>

#include "identify/pipeline/pipeline.hpp"
#include "identify/friction/shape_selection.hpp"
#include "robot/presliding_model.hpp"

namespace jacobid::identify {

struct PreslidingDisplacementChoice {
    std::vector<double> candidates;  // rad
    ShapeChoice shape;
    std::vector<double> displacement;  // rad per joint, the value used (the fallback where not chosen)
};

// 5e-5 * 2^(k/2), k = 0..12: 5e-5 .. 3.2e-3 rad.
std::vector<double> default_presliding_candidates();

// `model` is a PreslidingModel (its FDj columns are the ones the candidates replace); `fallback` the
// description's common x_p, kept by the joints that do not move.
PreslidingDisplacementChoice choose_presliding_displacement(const robot::PreslidingModel& model, const LogColumns& log,
                                                            const PipelineSettings& settings, double fallback, bool weighted,
                                                            std::vector<double> candidates = {});

// One line for the report: each joint's x_p, chosen or kept (and why).
std::string describe(const PreslidingDisplacementChoice& choice, const std::vector<std::string>& joint_names);

}  // namespace jacobid::identify
