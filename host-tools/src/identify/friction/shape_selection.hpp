// SPDX-License-Identifier: MIT
#pragma once
// Choosing a friction shape parameter per joint on held-out data (docs/method.md, "Coulomb smoothing from
// data"): the Coulomb smoothing alpha (coulomb_smoothing.hpp) and the presliding displacement x_p
// (presliding_displacement.hpp). One parameter per joint (FCj, FDj) has a family of candidate columns, one
// per candidate shape value, on the joint's own row:
//   1. one pipeline run on a candidate model: the nominal regressor plus every joint's candidate columns,
//      through the same differentiators, F_p and decimation as the final fit;
//   2. per joint and per contiguous block of the log, the normal equations over [nominal columns, the
//      joint's candidate columns, Y] (blocked cross-validation, contiguous blocks keep correlated
//      neighbours out of a held-out row's fit);
//   3. one common value first: smallest sum over the joints of the held-out MSE relative to the joint's mean
//      square torque;
//   4. then per joint, by coordinate descent, a joint leaves the common value only for a candidate whose
//      held-out error is lower by more than one standard error of the block-by-block difference.
#include <string>
#include <vector>

#include "identify/pipeline/pipeline.hpp"
#include "robot/robot_model.hpp"

namespace jacobid::identify {

// The candidate columns of one shape parameter: values(j, ...) writes joint j's candidate columns at one
// sample, from the joint velocities or from the candidate history this object integrates along the log.
class CandidateColumns {
public:
    virtual ~CandidateColumns() = default;
    virtual int history_size() const { return 0; }
    virtual void integrate_history(const std::vector<const std::vector<double>*>& q, std::vector<double>& state) const {
        (void)q;
        state.clear();
    }
    virtual void values(int joint, const double* qd, const double* history, double* out) const = 0;
};

struct ShapeSelectionSettings {
    std::vector<double> candidates;  // shape values, in the order of CandidateColumns::values
    std::vector<int> target;         // per joint: the nominal column the candidates replace (-1: none)
    std::vector<int> start;          // per joint: the candidate index to start from
    int folds = 5;
    bool weighted = false;           // fit as identify --weighted does
};

struct JointShape {
    bool chosen = false;
    std::string reason;               // why not chosen
    int index = -1;                   // chosen candidate
    std::vector<double> heldout_rms;  // N.m, per candidate, the other joints at their choice of the last pass
};

struct ShapeChoice {
    int folds = 0;
    int passes = 0;
    int common = -1;                   // step 3's candidate (-1: no joint chosen)
    std::vector<double> common_score;  // per candidate
    std::vector<JointShape> joints;
};

ShapeChoice choose_shape(const robot::RobotModel& model, const CandidateColumns& columns, const LogColumns& log, const PipelineSettings& settings,
                         const ShapeSelectionSettings& selection);

}  // namespace jacobid::identify
