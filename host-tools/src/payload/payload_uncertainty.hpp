// SPDX-License-Identifier: MIT
#pragma once
// What the payload's std inherits beyond the least squares' own (docs/method.md, "Payload identification"),
// first-order through phi = H^-1 A^T S t with H = A^T S A over the free payload columns of the solved factors:
//   - the arm's parameters (held): dphi/dtheta = -H^-1 A^T S D (D: the factors' arm block, W or W - W'), with
//     the arm's identified std, independent (identify writes no correlations);
//   - each joint's drive gain, a relative error scaling its effort: dphi/ddelta_j = H^-1 A^T S Y_j, with
//     --gain-std; and the mass's sensitivity to each gain whatever is given.
// Fills cov_arm, cov_gain, mass_gain_sensitivity, included and left_out of `out`.
#include <vector>

#include "identify/solve/least_squares.hpp"
#include "payload/arm_file.hpp"
#include "payload/payload_estimate.hpp"

namespace jacobid::payload {

// solved: the factors as solved (known and prior columns moved to the right-hand side); free: the payload
// parameters solved for (indices 0..9); difference: rows from --unloaded.
void add_inherited_uncertainty(PayloadEstimate& out, const identify::JointFactors& solved, const std::vector<int>& free, const ArmModel& arm,
                               bool difference, const std::vector<double>& gain_std);

}  // namespace jacobid::payload
