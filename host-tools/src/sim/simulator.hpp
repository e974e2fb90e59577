// SPDX-License-Identifier: MIT
#pragma once
// Closed-loop simulation of a robot model: PD position control tracking quintic point-to-point moves.
//
//  - The loop itself (controller, drive, integrator) is sim/closed_loop.hpp, shared with the estimators.
//  - Dynamics: forward dynamics from the model's regressor and the true parameters (robot::ForwardDynamics),
//    integrated with classic RK4 at control_rate * substeps (5 kHz by default).
//  - Control at control_rate (1 kHz): u = Kp (q_ref - q) + Kd (qd_ref - qd), Kp = M_jj(q0) omega^2,
//    Kd = 2 zeta M_jj(q0) omega, so each joint's position loop has roughly the wanted bandwidth omega_dyn.
//    The controller sees the true state: the measurement model only corrupts the log, so the motion (and
//    hence what identification has to explain) does not depend on the encoder resolution.
//  - The drive's current loop interpolates each command linearly over one control period (first-order
//    hold, one period of latency). The motor torque is then continuous, and the logged torque at t is the
//    torque acting at t: the log is consistent with tau = D(q, qd, qdd) X at every sample, with no
//    half-period shift that a zero-order hold would put between torque and motion.
#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <vector>

#include "robot/robot_description.hpp"
#include "robot/robot_model.hpp"
#include "sim/measurement.hpp"
#include "sim/quintic_trajectory.hpp"

namespace jacobid::sim {

struct SimulationSettings {
    double duration = 30.0;      // s
    double output_rate = 1000.0;  // Hz; must divide control_rate * substeps
    double control_rate = 1000.0;  // Hz
    int substeps = 5;            // RK4 steps per control period
    double omega_dyn = 30.0;     // rad/s, wanted bandwidth of each joint's position loop
    double damping = 1.0;        // zeta of the PD loop
    MoveSettings moves{};
    std::uint64_t seed = 1;      // trajectory seed (the measurement model has its own)
    // Explicit PD gains per joint (the robot description's controller); empty: from omega_dyn and damping.
    Eigen::VectorXd kp, kd;
    // A given reference (simulate --trajectory) instead of the random moves, and where it starts (the robot
    // starts there at rest); empty: the random moves.
    std::function<void(double t, ReferenceSample& out)> reference;
    std::vector<double> reference_start;
    // Simulated contacts (sim/external_torque.hpp): the torque acting on the joints besides the motor's at t;
    // empty: none.
    std::function<void(double t, Eigen::VectorXd& out)> external_torque;
};

// One logged sample: truth and measurement.
struct SimulatedSample {
    double t = 0.0;
    Eigen::VectorXd q, qd, qdd, tau;  // truth (tau = motor torque acting at t)
    Eigen::VectorXd q_measured, tau_measured;
    Eigen::VectorXd q_ref, qd_ref;  // the reference the controller tracked (at the last control instant)
    Eigen::VectorXd tau_external;   // truth: the external torque acting at t (zero without contacts)
};

// Number of samples simulate() will emit: floor(duration * output_rate) + 1 (t = 0 included).
std::size_t simulated_sample_count(const SimulationSettings& settings);

// Throws InputError (naming the option) for invalid settings, e.g. an output rate that does not divide
// the integration rate.
void validate(const SimulationSettings& settings);

// Runs the simulation and hands every output sample to `sink` (in time order). `parameters` are the true
// base parameters (model order), `joints` supply the limits of the random targets.
void simulate(const robot::RobotModel& model, const Eigen::VectorXd& parameters, const std::vector<robot::JointDescription>& joints,
              const SimulationSettings& settings, MeasurementModel& measurement,
              const std::function<void(const SimulatedSample&)>& sink);

// What a logger on the robot would have recorded: the measured positions (rad) and torques (N.m), one
// vector per joint, every 1 / output_rate seconds from t = 0 (for identify::log_columns).
struct MeasuredLog {
    double sample_period = 0.0;
    std::vector<std::vector<double>> q, tau;
    std::vector<std::vector<double>> q_ref, qd_ref;  // the reference tracked (for --estimator iv | didim)
};

// simulate() kept in memory as a MeasuredLog.
MeasuredLog simulate_log(const robot::RobotModel& model, const Eigen::VectorXd& parameters, const std::vector<robot::JointDescription>& joints,
                         const SimulationSettings& settings, MeasurementModel& measurement);

}  // namespace jacobid::sim
