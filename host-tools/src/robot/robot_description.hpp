#pragma once
// Robot description file (YAML), e.g.
//
//   model: planar2r          # the only model so far; a later issue adds serial chains from MDH/URDF
//   L1: 0.5                  # m
//   joints:                  # optional; defaults: names j1, j2, columns q1, q2 and tau1, tau2
//     - {name: shoulder, position: q1, torque: tau1, limits: [-2.5, 2.5]}
//     - {name: elbow,    position: q2, torque: tau2, limits: [-2.5, 2.5]}
//   friction:
//     coulomb: smooth        # sign | smooth (2/pi atan(alpha qd))
//     alpha: 100             # s/rad
//     offset: false          # constant friction offset per joint (FOFF1, FOFF2)
//   rotor_inertia: false     # separate rotor inertia of joint 2 (IA2)
//   parameters: {ZZ1R: 3.496, ...}  # optional: true values, used by `jacobid simulate`
//
// Errors are InputError "file:line:column: message" naming the key.
#include <Eigen/Core>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "jacobid/robot/coulomb_sign.hpp"
#include "robot/robot_model.hpp"

namespace jacobid::robot {

struct JointDescription {
    std::string name;
    std::string position_column;
    std::string torque_column;
    double lower_limit = -2.5;  // rad, used by the simulator's random targets
    double upper_limit = 2.5;
};

struct RobotDescription {
    std::string source = "<default>";
    std::string model = "planar2r";
    double L1 = 0.5;
    std::vector<JointDescription> joints;
    CoulombSign coulomb{CoulombModel::SmoothAtan, 100.0};
    bool friction_offset = false;
    bool rotor_inertia = false;
    std::vector<std::pair<std::string, double>> parameters;  // in file order; empty: not given
};

// The paper-like default: planar2r, L1 = 0.5 m, smoothed Coulomb friction (alpha = 100), joints j1, j2.
RobotDescription default_planar2r_description();
RobotDescription load_robot_description(const std::string& path);
RobotDescription parse_robot_description(const std::string& yaml_text, const std::string& source);

// The model the description names. InputError for an unknown model.
std::unique_ptr<RobotModel> make_robot_model(const RobotDescription& description);

// True parameter values for simulation, in model order: the model's reference values (the paper's Table II
// for planar2r), overridden by the description's `parameters`.
Eigen::VectorXd true_parameters(const RobotDescription& description, const RobotModel& model);

// The description as YAML (round-trips through parse_robot_description).
std::string to_yaml(const RobotDescription& description);

}  // namespace jacobid::robot
