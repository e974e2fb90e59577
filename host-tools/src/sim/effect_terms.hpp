// SPDX-License-Identifier: MIT
#pragma once
// Physical effects that a nominal rigid-body model misses, each written as regressor columns that are linear
// in the effect's magnitude once its hyper-parameter (Stribeck velocity, cogging order) is fixed. The same
// columns serve the simulator (truth dynamics = nominal model + effect columns with the injected values) and
// `jacobid diagnose` (candidate columns appended to the nominal regressor), so the two cannot disagree on
// what an effect is.
//
// Per joint j (one row of the regressor, the other rows 0):
//   coulomb_offset     1                                   value: offset, N.m
//   coulomb_asymmetry  |s(qd_j)|                           value: half the difference of the Coulomb levels
//                                                          per direction (FC+ = FC + a, FC- = FC - a), N.m
//   stribeck           s(qd_j) exp(-(qd_j / vs)^2)         value: static minus Coulomb friction FS - FC, N.m
//   viscous_nonlinear  qd_j |qd_j|                         value: N.m s^2 / rad^2
//   cogging            sin(k q_j), cos(k q_j)              value: amplitude, N.m (k = order, harmonics per rev)
//   rotor_inertia      qdd_j                               value: kg m^2
//   coulomb_smoothing  2/pi atan(alpha' qd_j)              value: the Coulomb level carried by a smoothing alpha'
//                                                          (s/rad) other than the description's, N.m: a
//                                                          named one says the joint's friction transition is
//                                                          better described at alpha' (friction: alpha)
//   coulomb_load       |g_j(q)| s(qd_j)                    value: Coulomb friction per N.m of the joint's gravity
//                                                          load g_j under the description's parameters (N.m
//                                                          per N.m; friction: coulomb_load, FCLj,
//                                                          robot/load_friction_model.hpp); only for joints
//                                                          gravity loads
//   presliding         s_j, the joint's Dahl state          value: presliding friction level FD, N.m (x_p = the
//                      (robot/presliding_model.hpp)        presliding displacement, rad). A history column: s_j
//                                                          depends on the position path, not on one state, so
//                                                          term_columns leaves it 0 and the models integrate it
//                                                          along the positions (AugmentedModel's history)
// Whole robot:
//   gravity            planar2r only: a tilted base puts g sin(tilt) into the plane of motion. With
//                      U = -(a1 cos q1 + b1 sin q1 + a2 cos q12 + b2 sin q12) the columns are
//                      [s1; 0], [-c1; 0], [s12; s12], [-c12; -c12]; value: sqrt(a1^2 + b1^2), the peak
//                      gravity torque of link 1 (and the mass it carries) on joint 1, N.m
//   torque_delay       not a column: the torque channel lags the position channel, value: delay, s
// s() is the Coulomb sign function of the robot description (exact or smoothed), so an effect reads the
// velocity exactly as the nominal friction does.
#include <Eigen/Core>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "jacobid/robot/coulomb_sign.hpp"
#include "robot/load_friction_model.hpp"

namespace jacobid::sim {

enum class EffectKind {
    CoulombOffset, CoulombAsymmetry, Stribeck, ViscousNonlinear, Gravity, Cogging, RotorInertia, TorqueDelay, Presliding, CoulombSmoothing,
    CoulombLoad
};

constexpr EffectKind kAllEffects[] = {EffectKind::CoulombOffset, EffectKind::CoulombAsymmetry, EffectKind::Stribeck,
                                      EffectKind::ViscousNonlinear, EffectKind::Gravity,         EffectKind::Cogging,
                                      EffectKind::RotorInertia,     EffectKind::TorqueDelay,     EffectKind::Presliding,
                                      EffectKind::CoulombSmoothing, EffectKind::CoulombLoad};

const char* effect_name(EffectKind kind);
std::optional<EffectKind> effect_kind(const std::string& name);
// Unit of an effect's value, e.g. "N.m".
const char* effect_unit(EffectKind kind);
// Effects that act on one joint (all but gravity and torque_delay).
bool effect_has_joint(EffectKind kind);
// Effects whose column depends on the path (a state integrated along the positions), not on one sample's
// q, qd, qdd: presliding.
bool effect_has_history(EffectKind kind);

// What the columns need to know about the robot.
struct EffectContext {
    std::string model_name;
    int joints = 0;
    robot::CoulombSign coulomb{};
    std::vector<robot::CoulombSign> joint_coulomb;  // per joint (friction.alpha per joint or auto); empty: coulomb
    double presliding_play = 2e-4;  // rad: the play operator's total width for presliding states (friction: presliding_play)
    // The reference gravity loads of coulomb_load (the description's parameters, law abs); null: no joint is loaded.
    std::shared_ptr<const robot::LoadFrictionModel> load{};
    const robot::CoulombSign& sign(int joint) const {
        return static_cast<std::size_t>(joint) < joint_coulomb.size() ? joint_coulomb[static_cast<std::size_t>(joint)] : coulomb;
    }
};

// One effect with its hyper-parameter fixed: a block of columns.
struct EffectTerm {
    EffectKind kind = EffectKind::CoulombOffset;
    int joint = -1;        // 0-based; -1 for whole-robot effects
    double velocity = 0;   // stribeck: vs in rad/s
    int order = 0;         // cogging: harmonic order per revolution
    double displacement = 0;  // presliding: x_p in rad
    double alpha = 0;         // coulomb_smoothing: alpha' in s/rad
    int column_count() const;
    // The same effect with the same hyper-parameters (what the selection names once).
    bool same_as(const EffectTerm& other) const;
    // A readable label, e.g. "cogging j2 k=6" (joints 1-based).
    std::string label() const;
    // Column names for parameter lists, e.g. "cogging2_k6_sin".
    std::vector<std::string> column_names() const;
};

// Whether the term exists for this robot (gravity needs the planar kinematics of planar2r).
bool term_applicable(const EffectTerm& term, const EffectContext& context, std::string* why_not = nullptr);

// Fills the term's columns (joints x column_count) at one state (zeros for a history effect). `load_factors`:
// context.load's factors at q when the caller has them (one gravity evaluation serves every coulomb_load term of
// a sample); null: evaluated here.
void term_columns(const EffectTerm& term, const EffectContext& context, const double* q, const double* qd, const double* qdd,
                  Eigen::Ref<Eigen::MatrixXd> columns, const double* load_factors = nullptr);

// The effect's scalar value from the term's coefficients (amplitude for cogging and gravity), and its
// standard deviation from their covariance (delta method).
double term_value(const EffectTerm& term, const Eigen::VectorXd& coefficients);
double term_value_std(const EffectTerm& term, const Eigen::VectorXd& coefficients, const Eigen::MatrixXd& covariance);

}  // namespace jacobid::sim
