// SPDX-License-Identifier: MIT
#pragma once
// `jacobid excite`'s optimizer (docs/excite.md): several starts of NLopt's MMA (information criteria) or SLSQP (cond, logdet; sequential quadratic
// programming with the exact gradients of excitation_problem.hpp) on the aggregated limits, the best
// feasible result kept, then every control sample checked; a limit missed between the optimizer's samples
// is tightened by the overshoot and the best result re-optimized (at most a few rounds).
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "excite/excitation_problem.hpp"

namespace jacobid::excite {

struct DesignSettings {
    int starts = 4;             // random starts
    int threads = 2;            // starts optimized side by side (each on its own copy of the problem)
    double time_limit = 60.0;   // s, all starts and rounds together
    std::uint64_t seed = 1;
    double control_rate = 1000.0;  // Hz: the rate at which every sample is checked
    int max_evaluations = 3000;    // per optimizer run (a start, a restart, a tightening round): --max-evaluations
    std::function<void(const std::string&)> progress;  // one line per start and round; null: silent
};

struct Design {
    Eigen::VectorXd coefficients;  // flattened, joint 0's first
    double criterion = 0.0;
    double cond = 0.0;
    LimitCheck check;
    std::optional<WorkspaceCheck> workspace;  // with the problem's workspace box: the point at every control sample
    int evaluations = 0;
    int starts_run = 0;
    int rounds = 0;  // tightening rounds after the first check
    double seconds = 0.0;
    std::vector<double> start_criteria;  // the final criterion of each start (NaN: infeasible)
};

// The problem's workspace box (if any) is the user's: it is tightened like the limits while optimizing and
// restored before returning. InputError when no start meets the limits (e.g. the pose's gravity torque already above a torque limit).
Design design_excitation(ExcitationProblem& problem, const robot::RobotModel& model, const Eigen::VectorXd& parameters,
                         const std::vector<JointLimits>& limits, const DesignSettings& settings);

}  // namespace jacobid::excite
