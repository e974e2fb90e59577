// SPDX-License-Identifier: MIT
#pragma once
// Physical plausibility of identified base parameters: which of them must be non-negative for ANY
// physically possible robot, and which identified values violate that.
//
// A base parameter is a combination base = sum_k c_k s_k of standard parameters (base_parameters.hpp).
// It is sign-constrained when every term is provably non-negative or completes a square that is:
//   masses M, rotor inertias IA, viscous FV and Coulomb FC coefficients, and the diagonal inertias
//   XX, YY, ZZ (about the link frame's origin) are >= 0, so they may appear with c_k >= 0;
//   a first moment (MZ_j = m_j z_j) may appear with coefficient b when the same link also brings an inertia
//   term a about an axis perpendicular to z (XX_j, YY_j both contain m z^2) and a mass term c with
//   b^2 <= 4 a c: a (m z^2) + b (m z) + c m = m (a z^2 + b z + c) >= 0 (the parallel-axis square, e.g.
//   ZZ1R = ... + YY2 + 0.487 MZ2 + 0.0593 M2 of the PUMA 560);
//   products of inertia, friction offsets and first moments without their square make it unconstrained
//   (XX2R = XX2 - YY2 may be negative).
// This is a sufficient condition: a parameter it leaves unconstrained may still be positive on a given
// robot, but one it marks is never negative on a real one. docs/real-data.md shows it on the UR10e.
#include <string>
#include <vector>

#include "identify/solve/least_squares.hpp"
#include "robot/robot_model.hpp"

namespace jacobid::identify {

struct SignConstraint {
    int parameter = 0;  // base parameter index
    std::string why;    // "viscous friction", "mass", "inertia", ...
};

// The base parameters of `model` that must be >= 0.
std::vector<SignConstraint> sign_constraints(const robot::RobotModel& model);

struct PlausibilityViolation {
    std::string name;
    double value = 0.0;
    double std_dev = 0.0;
    double rel_std_percent = 0.0;
    std::string why;
};

// Identified values below zero among the sign-constrained parameters (not-identified ones are skipped).
std::vector<PlausibilityViolation> plausibility_violations(const std::vector<SignConstraint>& constraints, const LsSolution& solution);

// "FV5 = -0.22 (%sigma_r 12.3) is negative: a viscous friction coefficient must be >= 0"
std::string describe(const PlausibilityViolation& v);

}  // namespace jacobid::identify
