// SPDX-License-Identifier: MIT
#include "sim/simulator.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>

#include "core/errors.hpp"
#include "jacobid/robot/presliding_friction.hpp"
#include "robot/presliding_model.hpp"
#include "sim/augmented_model.hpp"
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

    std::vector<double> lower, upper, start;
    for (int j = 0; j < n; ++j) {
        const auto& joint = joints[static_cast<std::size_t>(j)];
        lower.push_back(joint.lower_limit);
        upper.push_back(joint.upper_limit);
        start.push_back(std::clamp(0.0, joint.lower_limit, joint.upper_limit));
    }
    QuinticTrajectory trajectory(start, lower, upper, settings.moves, settings.seed);

    // PD gains from the wanted bandwidth and the inertia seen by each joint at the start configuration.
    const Eigen::MatrixXd M0 = dynamics.inertia(start.data());
    Eigen::VectorXd kp(n), kd(n);
    for (int j = 0; j < n; ++j) {
        kp[j] = M0(j, j) * settings.omega_dyn * settings.omega_dyn;
        kd[j] = 2.0 * settings.damping * M0(j, j) * settings.omega_dyn;
    }

    const double control_period = 1.0 / settings.control_rate;
    const double h = control_period / settings.substeps;
    const std::size_t output_every = steps_per_output(settings);
    const std::size_t samples = simulated_sample_count(settings);
    const std::size_t total_steps = (samples - 1) * output_every;

    Eigen::VectorXd q = Eigen::Map<const Eigen::VectorXd>(start.data(), n), qd = Eigen::VectorXd::Zero(n);
    Eigen::VectorXd u_prev = Eigen::VectorXd::Zero(n), u_cur = Eigen::VectorXd::Zero(n);
    double control_time = 0.0;
    ReferenceSample ref;
    // Motor torque at time t inside the current control period (first-order hold).
    Eigen::VectorXd tau(n);
    auto torque_at = [&](double t, Eigen::VectorXd& out) {
        const double s = std::clamp((t - control_time) / control_period, 0.0, 1.0);
        out = u_prev + s * (u_cur - u_prev);
    };
    // State derivative for RK4: (qd, qdd).
    Eigen::VectorXd k_q[4], k_qd[4];
    for (int i = 0; i < 4; ++i) {
        k_q[i].resize(n);
        k_qd[i].resize(n);
    }
    Eigen::VectorXd q_stage(n), qd_stage(n), tau_stage(n);
    // Presliding friction (a PreslidingModel): its Dahl state integrated along the true positions (no
    // quantization, no play), held over each integration step; the joints feel -FDj s_j, which the
    // controller's torque then carries into the log (docs/method.md, "Presliding friction (Dahl)").
    const auto* augmented = dynamic_cast<const AugmentedModel*>(&model);
    const auto* presliding = dynamic_cast<const robot::PreslidingModel*>(augmented ? &augmented->nominal() : &model);
    std::vector<robot::DahlState> dahl;
    Eigen::VectorXd held_friction = Eigen::VectorXd::Zero(n);
    if (presliding) {
        for (int j = 0; j < n; ++j) dahl.emplace_back(presliding->settings().displacement[static_cast<std::size_t>(j)]);
    }
    const auto update_presliding = [&](const Eigen::VectorXd& before, const Eigen::VectorXd& after) {
        for (std::size_t j = 0; j < dahl.size(); ++j) {
            const auto je = static_cast<Eigen::Index>(j);
            held_friction[je] = parameters[presliding->first_presliding_column() + je] * dahl[j].step(after[je] - before[je]);
        }
    };
    // True parameters no rigid body can have (a negative inertia) leave no dynamics to integrate.
    auto accelerations = [&](const Eigen::VectorXd& qs, const Eigen::VectorXd& qds, const Eigen::VectorXd& u, Eigen::VectorXd& qdd) {
        if (!dynamics.accelerations(qs.data(), qds.data(), u.data(), qdd.data())) {
            throw InputError("simulate: the robot's parameters give an inertia matrix that is not positive definite (a negative mass or inertia?)");
        }
    };
    auto derivative = [&](double t, const Eigen::VectorXd& qs, const Eigen::VectorXd& qds, Eigen::VectorXd& dq, Eigen::VectorXd& dqd) {
        torque_at(t, tau_stage);
        tau_stage -= held_friction;
        dq = qds;
        accelerations(qs, qds, tau_stage, dqd);
    };

    const double delay = measurement.settings().torque_delay;
    TorqueDelayLine delay_line(delay, 1.0 / settings.output_rate);
    SimulatedSample sample;
    sample.q.resize(n);
    sample.qd.resize(n);
    sample.qdd.resize(n);
    sample.tau.resize(n);
    sample.q_measured.resize(n);
    sample.tau_measured.resize(n);

    for (std::size_t step = 0;; ++step) {
        const double t = static_cast<double>(step) * h;
        if (step % static_cast<std::size_t>(settings.substeps) == 0) {
            trajectory.evaluate(t, ref);
            u_prev = u_cur;
            control_time = t;
            for (int j = 0; j < n; ++j) {
                const auto js = static_cast<std::size_t>(j);
                u_cur[j] = kp[j] * (ref.q[js] - q[j]) + kd[j] * (ref.qd[js] - qd[j]);
            }
        }
        if (step % output_every == 0) {
            torque_at(t, tau);
            sample.t = t;
            sample.q = q;
            sample.qd = qd;
            sample.tau = tau;
            accelerations(q, qd, tau - held_friction, sample.qdd);
            const Eigen::VectorXd& logged_tau = delay > 0.0 ? delay_line.push(tau) : tau;
            for (int j = 0; j < n; ++j) {
                sample.q_measured[j] = measurement.position(q[j]);
                sample.tau_measured[j] = measurement.torque(static_cast<std::size_t>(j), logged_tau[j], q[j]);
            }
            sink(sample);
        }
        if (step == total_steps) break;
        // RK4 over [t, t + h]; the torque is linear inside the control period.
        derivative(t, q, qd, k_q[0], k_qd[0]);
        q_stage = q + 0.5 * h * k_q[0];
        qd_stage = qd + 0.5 * h * k_qd[0];
        derivative(t + 0.5 * h, q_stage, qd_stage, k_q[1], k_qd[1]);
        q_stage = q + 0.5 * h * k_q[1];
        qd_stage = qd + 0.5 * h * k_qd[1];
        derivative(t + 0.5 * h, q_stage, qd_stage, k_q[2], k_qd[2]);
        q_stage = q + h * k_q[2];
        qd_stage = qd + h * k_qd[2];
        derivative(t + h, q_stage, qd_stage, k_q[3], k_qd[3]);
        q_stage = q;
        q += h / 6.0 * (k_q[0] + 2.0 * k_q[1] + 2.0 * k_q[2] + k_q[3]);
        qd += h / 6.0 * (k_qd[0] + 2.0 * k_qd[1] + 2.0 * k_qd[2] + k_qd[3]);
        update_presliding(q_stage, q);
    }
}

MeasuredLog simulate_log(const robot::RobotModel& model, const Eigen::VectorXd& parameters, const std::vector<robot::JointDescription>& joints,
                         const SimulationSettings& settings, MeasurementModel& measurement) {
    MeasuredLog log;
    log.sample_period = 1.0 / settings.output_rate;
    const auto n = static_cast<std::size_t>(model.joint_count());
    log.q.resize(n);
    log.tau.resize(n);
    const std::size_t samples = simulated_sample_count(settings);
    for (std::size_t j = 0; j < n; ++j) {
        log.q[j].reserve(samples);
        log.tau[j].reserve(samples);
    }
    simulate(model, parameters, joints, settings, measurement, [&](const SimulatedSample& s) {
        for (std::size_t j = 0; j < n; ++j) {
            log.q[j].push_back(s.q_measured[static_cast<Eigen::Index>(j)]);
            log.tau[j].push_back(s.tau_measured[static_cast<Eigen::Index>(j)]);
        }
    });
    return log;
}

}  // namespace jacobid::sim
