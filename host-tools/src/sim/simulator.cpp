// SPDX-License-Identifier: MIT
#include "sim/simulator.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "core/errors.hpp"
#include "core/measurable_motion.hpp"
#include "sim/closed_loop.hpp"
#include "sim/dahl_friction.hpp"
#include "sim/torque_delay_line.hpp"

namespace jacobid::sim {
namespace {

std::size_t steps_per_output(const SimulationSettings& s) {
    const double ratio = s.control_rate * s.substeps / s.output_rate;
    return static_cast<std::size_t>(std::llround(ratio));
}

}  // namespace

void validate(const SimulationSettings& s) {
    if (!(s.duration > 0.0) || !std::isfinite(s.duration)) throw InputError("--duration must be a finite number of seconds > 0");
    if (!(s.control_rate > 0.0) || !std::isfinite(s.control_rate)) throw InputError("--control-rate must be > 0 Hz");
    if (s.substeps < 1) throw InputError("--substeps must be >= 1");
    if (!(s.output_rate > 0.0) || !std::isfinite(s.output_rate)) throw InputError("--rate must be > 0 Hz");
    const double ratio = s.control_rate * s.substeps / s.output_rate;
    if (ratio < 1.0 - 1e-9 || std::abs(ratio - std::round(ratio)) > 1e-9 * ratio) {
        throw InputError(fmt::format("--rate {} Hz must divide the integration rate {} Hz (control rate x substeps)", s.output_rate,
                                     s.control_rate * s.substeps));
    }
    if (!(s.omega_dyn > 0.0)) throw InputError("--omega-dyn must be > 0 rad/s");
    if (s.omega_dyn * s.damping > 0.3 * 2.0 * M_PI * s.control_rate) {
        throw InputError(fmt::format("--omega-dyn {} rad/s is too high for a {} Hz controller", s.omega_dyn, s.control_rate));
    }
    if (!(s.moves.min_duration > 0.0) || s.moves.max_duration < s.moves.min_duration) {
        throw InputError("--move-duration: need 0 < min <= max seconds");
    }
    if (s.moves.max_dwell < 0.0) throw InputError("--dwell must be >= 0 s");
    // Limits under which no move can show a measurable motion within the run (core/measurable_motion.hpp).
    for (const double v : s.moves.velocity_limit) {
        const double reach = v * s.duration / kQuinticPeakVelocity;
        if (reach >= kMinMeasurableMotion) continue;
        throw InputError(fmt::format("--velocity-limit {:g} rad/s: a move within --duration {:g} s reaches at most v T / 1.875 = {:.3g} rad, less than "
                                     "the {:g} rad (or m) a log needs to show motion; raise the limit or --duration",
                                     v, s.duration, reach, kMinMeasurableMotion));
    }
    for (const double a : s.moves.acceleration_limit) {
        const double reach = a * s.duration * s.duration / kQuinticPeakAcceleration;
        if (reach >= kMinMeasurableMotion) continue;
        throw InputError(fmt::format("--acceleration-limit {:g} rad/s^2: a move within --duration {:g} s reaches at most a T^2 / 5.77 = {:.3g} rad, "
                                     "less than the {:g} rad (or m) a log needs to show motion; raise the limit or --duration",
                                     a, s.duration, reach, kMinMeasurableMotion));
    }
}

std::size_t simulated_sample_count(const SimulationSettings& s) {
    return static_cast<std::size_t>(std::floor(s.duration * s.output_rate + 1e-9)) + 1;
}

void simulate(const robot::RobotModel& model, const Eigen::VectorXd& parameters, const std::vector<robot::JointDescription>& joints,
              const SimulationSettings& settings, MeasurementModel& measurement,
              const std::function<void(const SimulatedSample&)>& sink) {
    validate(settings);
    const int n = model.joint_count();
    robot::ForwardDynamics dynamics(model, parameters);
    if (settings.reference && static_cast<int>(settings.reference_start.size()) != n) {
        throw InputError(fmt::format("--trajectory: starts with {} joints, the robot has {}", settings.reference_start.size(), n));
    }

    const Eigen::VectorXd q0 = settings.reference ? Eigen::Map<const Eigen::VectorXd>(settings.reference_start.data(), n).eval() : start_configuration(joints);
    const std::vector<double> start(q0.data(), q0.data() + n);
    std::vector<double> lower, upper;
    for (const auto& joint : joints) {
        lower.push_back(joint.lower_limit);
        upper.push_back(joint.upper_limit);
    }
    QuinticTrajectory trajectory(start, lower, upper, settings.moves, settings.seed);

    // PD gains: given (the description's controller), or from the wanted bandwidth and the inertia seen by
    // each joint at the start configuration.
    PdGains gains{settings.kp, settings.kd};
    if (gains.kp.size() == 0) gains = bandwidth_gains(dynamics, q0, settings.omega_dyn, settings.damping);

    ClosedLoopSettings loop;
    loop.control_rate = settings.control_rate;
    loop.substeps = settings.substeps;
    loop.steps_per_output = steps_per_output(settings);
    loop.samples = simulated_sample_count(settings);
    loop.external = settings.external_torque;

    const double delay = measurement.settings().torque_delay;
    TorqueDelayLine delay_line(delay, 1.0 / settings.output_rate);
    SimulatedSample sample;
    sample.q_measured.resize(n);
    sample.tau_measured.resize(n);
    sample.q_ref.resize(n);
    sample.qd_ref.resize(n);
    const std::unique_ptr<DahlFriction> dahl = presliding_friction(model, parameters);
    // True parameters no rigid body can have (a negative inertia) leave no dynamics to integrate.
    run_closed_loop(
        dynamics, q0, Eigen::VectorXd::Zero(n), gains, loop, [&](double t, ReferenceSample& ref) { settings.reference ? settings.reference(t, ref) : trajectory.evaluate(t, ref); },
        "simulate: the robot's parameters give an inertia matrix that is not positive definite (a negative mass or inertia?)",
        [&](const ClosedLoopSample& s) {
            sample.t = s.t;
            sample.q = *s.q;
            sample.qd = *s.qd;
            sample.qdd = *s.qdd;
            sample.tau = *s.tau;
            sample.tau_external = *s.external;
            const Eigen::VectorXd& logged_tau = delay > 0.0 ? delay_line.push(*s.tau) : *s.tau;
            for (int j = 0; j < n; ++j) {
                const auto js = static_cast<std::size_t>(j);
                sample.q_measured[j] = measurement.position((*s.q)[j]);
                sample.tau_measured[j] = measurement.torque(js, logged_tau[j], (*s.q)[j]);
                sample.q_ref[j] = s.reference->q[js];
                sample.qd_ref[j] = s.reference->qd[js];
            }
            require_finite_state(s.t, {{"measured position", &sample.q_measured}, {"measured torque", &sample.tau_measured}},
                                 "--position-noise, --torque-noise, --ripple or an injected effect beyond what a double holds");
            sink(sample);
        },
        dahl.get());
}

MeasuredLog simulate_log(const robot::RobotModel& model, const Eigen::VectorXd& parameters, const std::vector<robot::JointDescription>& joints,
                         const SimulationSettings& settings, MeasurementModel& measurement) {
    MeasuredLog log;
    log.sample_period = 1.0 / settings.output_rate;
    const auto n = static_cast<std::size_t>(model.joint_count());
    const std::size_t samples = simulated_sample_count(settings);
    for (auto* columns : {&log.q, &log.tau, &log.q_ref, &log.qd_ref}) {
        columns->resize(n);
        for (auto& c : *columns) c.reserve(samples);
    }
    simulate(model, parameters, joints, settings, measurement, [&](const SimulatedSample& s) {
        for (std::size_t j = 0; j < n; ++j) {
            log.q[j].push_back(s.q_measured[static_cast<Eigen::Index>(j)]);
            log.tau[j].push_back(s.tau_measured[static_cast<Eigen::Index>(j)]);
            log.q_ref[j].push_back(s.q_ref[static_cast<Eigen::Index>(j)]);
            log.qd_ref[j].push_back(s.qd_ref[static_cast<Eigen::Index>(j)]);
        }
    });
    return log;
}

}  // namespace jacobid::sim
