// SPDX-License-Identifier: MIT
#pragma once
// Robot description file (YAML), e.g.
//
//   model: planar2r          # planar2r | mdh | urdf
//   L1: 0.5                  # m (planar2r only)
//   joints:                  # optional; defaults: names j1, j2, columns q1, q2 and tau1, tau2
//     - {name: shoulder, position: q1, torque: tau1, limits: [-2.5, 2.5]}
//     - {name: elbow,    position: q2, torque: tau2, limits: [-2.5, 2.5]}
//   friction:
//     coulomb: smooth        # sign | smooth (2/pi atan(alpha qd))
//     alpha: auto            # s/rad: auto (default: chosen per joint on held-out data), a number, or one per joint
//     offset: false          # constant friction offset per joint (FOFF1, FOFF2)
//     coulomb_load: none     # none | abs | square: Coulomb friction growing with the joint's gravity load, FCLj (robot/load_friction_model.hpp)
//     presliding: none       # none | dahl: presliding friction with memory, FDj s_j (robot/presliding_model.hpp)
//     presliding_displacement: auto  # rad: auto (chosen per joint on held-out data), a number, or one per joint
//     presliding_play: 2e-4  # rad: total width of the play operator that removes quantization flicker (0: none)
//   rotor_inertia: false     # separate rotor inertia of joint 2 (IA2)
//   parameters: {ZZ1R: 3.496, ...}  # optional: true values, used by `jacobid simulate`
//   controller: {omega: 30, damping: 1, rate: 1000}  # optional: the position loop (controller_description.hpp)
//
// Serial robots (docs/robots.md):
//
//   model: mdh               # modified DH (Khalil-Kleinfinger), one row per joint
//   gravity: [0, 0, -9.81]   # m/s^2 in the base frame (mdh and urdf; default shown)
//   joints:
//     - {name: j1, sigma: 0, alpha: 0, d: 0, theta: 0, r: 0, antecedent: 0, limits: [-2.5, 2.5], position: q1, torque: tau1}
//   parameters: {ZZ1: 1.2, M2: 3.0, FV1: 0.2, ...}   # STANDARD parameters (XXj ... Mj, IAj, FVj, FCj, FOFFj)
//
//   model: urdf
//   urdf: arm.urdf           # relative to this file; inertials and <dynamics> give default parameters
//   joints: [...]            # optional: names/columns/limits, one per movable URDF joint
//
// Errors are InputError "file:line:column: message" naming the key.
#include <Eigen/Core>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "jacobid/robot/coulomb_sign.hpp"
#include "jacobid/robot/kinematic_chain.hpp"
#include "jacobid/robot/mdh_joint.hpp"
#include "robot/controller_description.hpp"
#include "robot/load_friction_model.hpp"
#include "robot/presliding_model.hpp"
#include "robot/robot_model.hpp"

namespace jacobid::robot {

struct JointDescription {
    std::string name;
    std::string position_column;
    std::string torque_column;
    double lower_limit = -2.5;  // rad, used by the simulator's random targets
    double upper_limit = 2.5;
    bool limits_given = false;  // by the description's `limits:` or a URDF <limit> (not the defaults): logs are checked against them
};

struct RobotDescription {
    std::string source = "<default>";
    std::string model = "planar2r";
    double L1 = 0.5;
    std::vector<JointDescription> joints;
    CoulombSign coulomb{CoulombModel::SmoothAtan, 100.0};
    // friction.alpha: `auto` (the default) lets identify and diagnose choose each joint's smoothing on held-out
    // data (identify/friction/coulomb_smoothing.hpp); until then, and in simulation, coulomb.alpha applies.
    bool coulomb_alpha_auto = true;
    std::vector<double> coulomb_alpha;  // s/rad per joint (a list in the file, or chosen); empty: coulomb.alpha for all
    bool friction_offset = false;
    // friction.coulomb_load: abs | square adds FCLj |g_j(q)| s_j(qd_j) (or g_j^2) per joint that gravity loads, g_j
    // from the description's own parameters (docs/method.md, "Load-dependent Coulomb friction").
    CoulombLoad coulomb_load = CoulombLoad::none;
    // friction.presliding: dahl (docs/method.md, "Presliding friction (Dahl)"). presliding_displacement:
    // `auto` (the default) lets identify choose x_p per joint on held-out data
    // (identify/friction/presliding_displacement.hpp); until then, and in simulation, the common value applies.
    bool presliding = false;
    bool presliding_displacement_auto = true;
    double presliding_displacement = 3e-4;                // rad, every joint
    std::vector<double> presliding_displacements;         // rad per joint (a list, or chosen); empty: the common value
    double presliding_play = 2e-4;                        // rad, play operator's total width
    bool rotor_inertia = false;
    std::vector<std::pair<std::string, double>> parameters;  // in file order; empty: not given
    std::optional<ControllerDescription> controller;         // the position loop (simulate, identify --estimator iv|didim)
    // Serial robots (model mdh or urdf).
    Eigen::Vector3d gravity{0.0, 0.0, -9.81};  // m/s^2, base frame
    std::vector<MdhJoint> mdh;                 // model mdh: the table as written
    std::string urdf;                          // model urdf: resolved path of the URDF file
    std::vector<ChainJoint> chain;             // mdh and urdf: the kinematic chain
    std::vector<std::pair<std::string, double>> model_parameters;  // urdf: standard values from the file
};

// The paper-like default: planar2r, L1 = 0.5 m, smoothed Coulomb friction (alpha = 100), joints j1, j2.
RobotDescription default_planar2r_description();
RobotDescription load_robot_description(const std::string& path);
RobotDescription parse_robot_description(const std::string& yaml_text, const std::string& source);

// Each joint's Coulomb sign function: coulomb with the joint's alpha (coulomb_alpha) when given.
std::vector<CoulombSign> joint_coulomb_signs(const RobotDescription& description);

// The model the description names (wrapped in a LoadFrictionModel with coulomb_load, then in a
// PreslidingModel with presliding: dahl). InputError for an unknown model.
std::unique_ptr<RobotModel> make_robot_model(const RobotDescription& description);
// The description's reference gravity loads (its own rigid-body parameters) as a LoadFrictionModel of law
// abs, whatever its friction: coulomb_load says (what diagnose's coulomb_load candidates and simulate's
// coulomb_load effect read); null when gravity loads no joint.
std::shared_ptr<const LoadFrictionModel> gravity_load_reference(const RobotDescription& description);
// The presliding settings of the description's joints (displacement per joint, play width).
PreslidingSettings presliding_settings(const RobotDescription& description);

// True parameter values for simulation, in model order: the model's reference values (the paper's Table II
// for planar2r), overridden by the description's `parameters`. Serial models: the description's standard
// parameters (URDF inertials, overridden by `parameters`, others 0) mapped to base parameters by the
// regrouping.
Eigen::VectorXd true_parameters(const RobotDescription& description, const RobotModel& model);
// A serial model's standard parameters from the description (URDF inertials, overridden by `parameters`,
// others 0), in the model's standard order: the values true_parameters regroups.
class SerialRobotModel;
Eigen::VectorXd standard_values(const RobotDescription& description, const SerialRobotModel& model);

// The description as YAML (round-trips through parse_robot_description).
std::string to_yaml(const RobotDescription& description);

}  // namespace jacobid::robot
