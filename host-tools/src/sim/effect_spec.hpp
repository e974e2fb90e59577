// SPDX-License-Identifier: MIT
#pragma once
// Effects injected by `jacobid simulate`: which effect, on which joint, how large. Two spellings:
//
//   --effect NAME:key=value,key=value     (repeatable), e.g.
//       --effect coulomb_offset:joint=1,value=0.3 --effect cogging:joint=2,amplitude=0.2,order=6
//   --effects FILE.yaml                   effects: [{name: stribeck, joint: 1, value: 0.3, velocity: 0.1}, ...]
//
// Keys (joints 1-based, SI units, angles in degrees):
//   coulomb_offset     joint, value (N.m)
//   coulomb_asymmetry  joint, value (N.m: FC+ = FC + value, FC- = FC - value)
//   stribeck           joint, value (N.m, FS - FC), velocity (rad/s, vs; default 0.1)
//   viscous_nonlinear  joint, value (N.m s^2/rad^2, times qd |qd|)
//   cogging            joint, amplitude (N.m; alias value), order (per rev; default 6), phase (deg; default 0)
//   rotor_inertia      joint, value (kg m^2)
//   coulomb_smoothing  joint, value (N.m, a Coulomb level at another smoothing), alpha (s/rad; default 100)
//   presliding         joint, value (N.m, the Dahl level FD), displacement (rad, x_p; default 5e-4); the state is
//                      integrated along the true positions as with friction: {presliding: dahl}
//   gravity            tilt (deg), direction (deg, in-plane direction of the gravity component; default 0),
//                      mx1 (kg m, first moment of link 1 incl. the mass it carries; default 1.5)
//   torque_delay       value (s: the logged torque lags the positions by this much)
// Errors (InputError) name the offending token or file:line:column.
#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "robot/robot_model.hpp"
#include "sim/effect_terms.hpp"

namespace jacobid::sim {

struct EffectSpec {
    EffectKind kind = EffectKind::CoulombOffset;
    int joint = -1;          // 0-based, -1 for whole-robot effects
    double value = 0.0;      // the magnitude as the diagnosis reports it (for gravity: g sin(tilt) mx1)
    double velocity = 0.1;   // stribeck vs, rad/s
    double displacement = 5e-4;  // presliding x_p, rad
    double alpha = 100.0;        // coulomb_smoothing alpha', s/rad
    int order = 6;           // cogging harmonics per revolution
    double phase = 0.0;      // cogging phase, deg
    double tilt = 0.0;       // gravity: base tilt, deg
    double direction = 0.0;  // gravity: direction of the in-plane component, deg
    double mx1 = 1.5;        // gravity: first moment of link 1 (incl. carried mass), kg m
};

constexpr double kGravity = 9.80665;  // m/s^2

// One --effect token split at its colon and commas: NAME, then key=value pairs (InputError naming the token
// for an item that is not key=value); `where` names the token in later errors.
struct EffectToken {
    std::string name;
    std::vector<std::pair<std::string, std::string>> pairs;
    std::string where;
};
EffectToken split_effect_token(const std::string& token);
// The finite number `text` is, or InputError "<where>: '<text>' is not a finite number".
double number_or_throw(const std::string& text, const std::string& where);

// Parses one --effect token for a robot with `joints` joints.
EffectSpec parse_effect(const std::string& token, int joints);
// Parses an effects YAML file ("effects:" list of maps with a "name" key and the keys above).
std::vector<EffectSpec> load_effects_file(const std::string& path, int joints);
std::vector<EffectSpec> parse_effects_yaml(const std::string& yaml_text, const std::string& source, int joints);

// The columns of an effect (none for torque_delay) and their true coefficients. Gravity on link 2 uses the
// nominal MX2 and MY2 (0 if the model has none).
EffectTerm term_of(const EffectSpec& spec);
Eigen::VectorXd injected_coefficients(const EffectSpec& spec, const robot::RobotModel& nominal, const Eigen::VectorXd& nominal_parameters);

nlohmann::json to_json(const EffectSpec& spec);

}  // namespace jacobid::sim
