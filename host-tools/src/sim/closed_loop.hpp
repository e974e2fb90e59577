// SPDX-License-Identifier: MIT
#pragma once
// The closed loop of the simulated robot, shared by `jacobid simulate` (tracking its quintic moves) and by
// the estimators that simulate the identified model along a log's reference (IDIM-IV, DIDIM; docs/method.md,
// "Estimators"): one integrator, so that the instruments and the simulated regressor come from exactly
// the dynamics and the drive the simulated logs were written with.
//
//  - Control at control_rate: u = Kp (q_ref - q) + Kd (qd_ref - qd) from the state at the control instant.
//  - The drive interpolates each command linearly over one control period (first-order hold, one period
//    of latency), so the motor torque is continuous and the logged torque at t is the torque acting at t.
//  - Forward dynamics (robot::ForwardDynamics) integrated with classic RK4 at control_rate * substeps.
#include <Eigen/Core>
#include <cstddef>
#include <functional>
#include <initializer_list>
#include <utility>
#include <string>
#include <vector>

#include "robot/controller_description.hpp"
#include "robot/robot_description.hpp"
#include "robot/robot_model.hpp"
#include "sim/quintic_trajectory.hpp"

namespace jacobid::sim {

struct PdGains {
    Eigen::VectorXd kp, kd;  // per joint, N.m/rad and N.m s/rad
};

// Kp = M_jj(q0) omega^2, Kd = 2 zeta M_jj(q0) omega: each joint's position loop has roughly the bandwidth
// omega (rad/s) at q0 (the simulator's rule; `robot::ControllerDescription` with omega uses it too).
PdGains bandwidth_gains(robot::ForwardDynamics& dynamics, const Eigen::VectorXd& q0, double omega, double damping);

// Where the simulator starts: each joint at 0 clamped to its limits.
Eigen::VectorXd start_configuration(const std::vector<robot::JointDescription>& joints);

// The gains of a description's controller: its kp and kd, or bandwidth_gains at the start configuration
// with `truth` (dynamics of the description's true parameters, as `jacobid simulate` integrates).
PdGains described_gains(const robot::ControllerDescription& controller, robot::ForwardDynamics& truth, const std::vector<robot::JointDescription>& joints);

struct ClosedLoopSettings {
    double control_rate = 1000.0;      // Hz
    int substeps = 5;                  // RK4 steps per control period
    std::size_t steps_per_output = 5;  // RK4 steps between two output samples
    std::size_t samples = 0;           // output samples, the first at t = 0
    // A torque acting on the joints besides the motor's (simulated contacts, sim/external_torque.hpp): out at
    // time t, already sized; empty: none.
    std::function<void(double t, Eigen::VectorXd& out)> external;
};

// One output sample of the loop (valid during the sink call only).
struct ClosedLoopSample {
    std::size_t index = 0;
    double t = 0.0;
    const Eigen::VectorXd* q = nullptr;
    const Eigen::VectorXd* qd = nullptr;
    const Eigen::VectorXd* qdd = nullptr;
    const Eigen::VectorXd* tau = nullptr;  // motor torque acting at t
    const ReferenceSample* reference = nullptr;  // the reference of the last control instant
    const Eigen::VectorXd* external = nullptr;   // the external torque acting at t (zero without settings.external)
};

// A friction torque with memory (presliding, docs/method.md "Presliding friction (Dahl)"): held over each
// integration step, updated from the positions before and after it; the joints feel -torque.
class HeldFriction {
public:
    virtual ~HeldFriction() = default;
    virtual void step(const Eigen::VectorXd& before, const Eigen::VectorXd& after, Eigen::VectorXd& torque) = 0;
};

// Reference at control instant t (t never decreases between calls).
using ReferenceFunction = std::function<void(double t, ReferenceSample& out)>;

// InputError "simulation at t = ... s: joint j's <what> is not finite (<cause>)" for the first
// entry of `state` (what, values) that is not finite; nothing when all are.
void require_finite_state(double t, std::initializer_list<std::pair<const char*, const Eigen::VectorXd*>> state, const char* cause);

// Integrates the loop from rest state (q0, qd0). `failure` is the InputError message when the dynamics
// have no positive definite inertia matrix on the way (parameters no rigid body can have). `friction`, if
// given, acts on the joints besides the dynamics' own terms (the sample's tau stays the motor torque).
void run_closed_loop(robot::ForwardDynamics& dynamics, const Eigen::VectorXd& q0, const Eigen::VectorXd& qd0, const PdGains& gains,
                     const ClosedLoopSettings& settings, const ReferenceFunction& reference, const std::string& failure,
                     const std::function<void(const ClosedLoopSample&)>& sink, HeldFriction* friction = nullptr);

}  // namespace jacobid::sim
