// SPDX-License-Identifier: MIT
#pragma once
// A small dense interior-point solver (docs/method.md, "Physically consistent identification"):
//     minimise  x^T Q x - 2 c^T x   subject to  F_i(x) = sum_k x_k F_ik  positive definite,  i = 1..m
// by the log-barrier method (Boyd and Vandenberghe, Convex Optimization, ch. 11): Newton's method with a
// feasibility-keeping backtracking line search on t (x^T Q x - 2 c^T x) - sum_i log det F_i(x), t raised 20-fold
// per round. For a convex problem the result is the global minimum, certified to within the duality gap
// (sum of the blocks' sizes + the Newton decrement) / t, a bound that holds only at a (nearly) centred point:
// a round that stalls away from its centre ends the solve, unconverged. The blocks are small (4x4 pseudo-inertias, 1x1 bounds), so every Newton
// step is a dense solve over x.
#include <Eigen/Core>
#include <vector>

namespace jacobid::identify {

// F(x) = sum over terms of x[column] * matrix.
struct LmiBlock {
    struct Term {
        int column = 0;
        Eigen::MatrixXd matrix;
    };
    int size = 0;
    std::vector<Term> terms;
    Eigen::MatrixXd at(const Eigen::VectorXd& x) const;
};

struct BarrierSettings {
    double gap = 1e-6;     // stop when the duality-gap bound is below this (in the objective's units)
    int max_newton = 2000;  // Newton steps over all rounds
};

struct BarrierResult {
    Eigen::VectorXd x;
    double objective = 0.0;  // x^T Q x - 2 c^T x
    double gap = 0.0;        // duality-gap bound of x: (sum of block sizes + Newton decrement) / t
    int newton_steps = 0;
    bool converged = false;  // the gap reached BarrierSettings::gap at a centred point
};

// x0 must be strictly feasible (every block positive definite); std::invalid_argument otherwise.
BarrierResult minimise_with_lmis(const Eigen::MatrixXd& Q, const Eigen::VectorXd& c, const std::vector<LmiBlock>& blocks, Eigen::VectorXd x0,
                                 const BarrierSettings& settings = {});

}  // namespace jacobid::identify
