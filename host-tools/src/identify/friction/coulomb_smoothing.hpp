// SPDX-License-Identifier: MIT
#pragma once
// `friction: {alpha: auto}`: each joint's Coulomb smoothing 2/pi atan(alpha qd) chosen from the data
// (docs/method.md, "Coulomb smoothing from data"). The validation NRMSE of a real drive moves by several
// points between alpha 20 and 300, and the best value differs from joint to joint, so it is selected, not
// guessed, and never on the validation log:
//   1. one pipeline run on a candidate model: the nominal regressor plus, for every joint j with a Coulomb
//      parameter FCj and every candidate alpha a, the column s_a(qd_j) on joint j's row. The candidate
//      columns go through the same differentiators, F_p and decimation as the regressor, so what is
//      compared is exactly what the final identification will fit;
//   2. per joint and per contiguous block of the log, the normal equations over [nominal columns, the
//      joint's candidate columns, Y] (blocked cross-validation: a block is predicted by the fit on the others;
//      contiguous blocks keep a held-out row's correlated neighbours out of its fit);
//   3. one common alpha first: the candidate with the smallest sum over the joints of the held-out mean
//      squared error relative to the joint's mean square torque;
//   4. then per joint, by coordinate descent (the others held at their current choice), a joint leaves the
//      common value only for a candidate whose held-out error of that joint's torque is lower by more than
//      one standard error of the block-by-block difference; passes repeat until no choice changes (at most 4).
// Joints that do not move, or whose model has no FCj, keep the description's alpha and say why.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "identify/pipeline/pipeline.hpp"
#include "identify/friction/presliding_displacement.hpp"
#include "robot/robot_description.hpp"
#include "robot/robot_model.hpp"

namespace jacobid::identify {

struct CoulombSmoothingSettings {
    std::vector<double> candidates;  // s/rad; empty: 10 * 2^(k/2), k = 0..14 (10 .. 1280)
    int folds = 5;                   // contiguous blocks of the log
    bool weighted = false;           // fit as identify --weighted does (rows of joint j by 1 / sigma_j)
};

struct JointSmoothing {
    bool chosen = false;             // false: kept the description's alpha (reason says why)
    std::string reason;              // why not chosen
    double alpha = 0.0;              // s/rad, the value used
    std::vector<double> heldout_rms;  // N.m, per candidate, with the other joints at their choice of the last pass (empty if not chosen)
};

struct CoulombSmoothingChoice {
    std::vector<double> candidates;
    int folds = 0;
    int passes = 0;
    double common_alpha = 0.0;         // s/rad, step 1's choice for every joint (0: no joint chosen)
    std::vector<double> common_score;  // per candidate: sum over joints of held-out MSE / mean square torque
    std::vector<JointSmoothing> joints;
    std::vector<double> alphas() const;  // per joint, the value to use
};

std::vector<double> default_coulomb_candidates();

// `model` is built with `fallback_alpha` on every joint (its own FCj columns are replaced). The log is the
// one the identification will use (torque delay already compensated). InputError if the log is too short
// for the pipeline, as run_pipeline.
CoulombSmoothingChoice choose_coulomb_smoothing(const robot::RobotModel& model, const LogColumns& log, const PipelineSettings& settings,
                                                double fallback_alpha, const CoulombSmoothingSettings& smoothing = {});

// One line for the report: each joint's alpha, chosen or kept (and why).
std::string describe(const CoulombSmoothingChoice& choice, const std::vector<std::string>& joint_names);

// The model to identify with: the description's, or, with friction alpha: auto and smooth Coulomb friction,
// the one with each joint's alpha chosen on `log` (`choice` then says how). `nominal` is the description's model.
// With presliding: dahl and presliding_displacement: auto, each joint's x_p is chosen first (at the
// description's alpha), then alpha with the chosen x_p (`presliding` says how).
struct SmoothedModel {
    std::unique_ptr<robot::RobotModel> chosen;  // null: use `nominal` as it is
    std::optional<CoulombSmoothingChoice> choice;
    std::optional<PreslidingDisplacementChoice> presliding;
    const robot::RobotModel& get(const robot::RobotModel& nominal) const { return chosen ? *chosen : nominal; }
};
SmoothedModel resolve_coulomb_smoothing(const robot::RobotDescription& description, const robot::RobotModel& nominal, const LogColumns& log,
                                        const PipelineSettings& settings, bool weighted);
// m.chosen made from `description` with m's choices (presliding displacements, Coulomb alphas), as
// resolve_coulomb_smoothing makes it; null when there are none. A plan carried to another process
// (job/identify_plan.hpp) holds the choices only.
void make_chosen_model(const robot::RobotDescription& description, SmoothedModel& m);

}  // namespace jacobid::identify
