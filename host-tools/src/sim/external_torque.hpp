// SPDX-License-Identifier: MIT
#pragma once
// Simulated contacts: `jacobid simulate --effect external:joint=J,start=S,duration=D,value=V[,shape=...]`
// (docs/monitor.md). An external torque acts on joint J (1-based) from S for D seconds, besides the motor
// torque (M qdd + C qd + g + f = tau + tau_ext), with the shape
//   pulse (default)  V over [S, S + D),
//   sine             V sin(pi (t - S) / D): a half-sine bump, a smooth push,
//   ramp             V (t - S) / D rising over [S, S + D), then gone: a pressing contact that slips off.
// The truth is logged beside the measured columns (simulate's tau_ext1.. columns). Unlike the effects of
// effect_spec.hpp it is a function of time, not a column of the model: identification knows nothing of it.
#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace jacobid::sim {

enum class ContactShape { Pulse, Sine, Ramp };

struct ExternalTorque {
    int joint = 0;          // 0-based
    double start = 0.0;     // s
    double duration = 0.0;  // s, > 0
    double value = 0.0;     // N.m (N for a prismatic joint)
    ContactShape shape = ContactShape::Pulse;
};

// True when the --effect token names an external torque ("external:...").
bool is_external_torque(const std::string& token);
// Parses "external:joint=J,start=S,duration=D,value=V[,shape=pulse|sine|ramp]" for a robot of `joints`
// joints; InputError naming the token and key otherwise.
ExternalTorque parse_external_torque(const std::string& token, int joints);

// out (resized to `joints`) = the sum of the contacts' torques at t.
void external_torque_at(const std::vector<ExternalTorque>& contacts, double t, int joints, Eigen::VectorXd& out);

nlohmann::json to_json(const ExternalTorque& contact);

}  // namespace jacobid::sim
