// SPDX-License-Identifier: MIT
#include "sim/closed_loop.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "core/errors.hpp"

namespace jacobid::sim {

void require_finite_state(double t, std::initializer_list<std::pair<const char*, const Eigen::VectorXd*>> state, const char* cause) {
    for (const auto& [what, values] : state) {
        for (Eigen::Index j = 0; j < values->size(); ++j) {
            if (!std::isfinite((*values)[j])) throw InputError(fmt::format("simulation at t = {:.6g} s: joint {}'s {} is not finite ({})", t, j + 1, what, cause));
        }
    }
}

PdGains bandwidth_gains(robot::ForwardDynamics& dynamics, const Eigen::VectorXd& q0, double omega, double damping) {
    const Eigen::MatrixXd M0 = dynamics.inertia(q0.data());
    PdGains g;
    g.kp = M0.diagonal() * omega * omega;
    g.kd = M0.diagonal() * 2.0 * damping * omega;
    return g;
}

Eigen::VectorXd start_configuration(const std::vector<robot::JointDescription>& joints) {
    Eigen::VectorXd q0(static_cast<Eigen::Index>(joints.size()));
    for (std::size_t j = 0; j < joints.size(); ++j) q0[static_cast<Eigen::Index>(j)] = std::clamp(0.0, joints[j].lower_limit, joints[j].upper_limit);
    return q0;
}

PdGains described_gains(const robot::ControllerDescription& c, robot::ForwardDynamics& truth, const std::vector<robot::JointDescription>& joints) {
    if (c.kp.empty()) return bandwidth_gains(truth, start_configuration(joints), c.omega, c.damping);
    PdGains g;
    g.kp = Eigen::Map<const Eigen::VectorXd>(c.kp.data(), static_cast<Eigen::Index>(c.kp.size()));
    g.kd = Eigen::Map<const Eigen::VectorXd>(c.kd.data(), static_cast<Eigen::Index>(c.kd.size()));
    return g;
}

namespace {
constexpr const char* kDivergence =
    "the simulation diverged: parameters no robot can have, or an integration step too long for them; check the description and --substeps";
}  // namespace

void run_closed_loop(robot::ForwardDynamics& dynamics, const Eigen::VectorXd& q0, const Eigen::VectorXd& qd0, const PdGains& gains,
                     const ClosedLoopSettings& settings, const ReferenceFunction& reference, const std::string& failure,
                     const std::function<void(const ClosedLoopSample&)>& sink, HeldFriction* friction) {
    const Eigen::Index n = q0.size();
    const double control_period = 1.0 / settings.control_rate;
    const double h = control_period / settings.substeps;
    const std::size_t total_steps = settings.samples == 0 ? 0 : (settings.samples - 1) * settings.steps_per_output;

    Eigen::VectorXd q = q0, qd = qd0;
    Eigen::VectorXd u_prev = Eigen::VectorXd::Zero(n), u_cur = Eigen::VectorXd::Zero(n);
    double control_time = 0.0;
    ReferenceSample ref;
    // Motor torque at time t inside the current control period (first-order hold).
    auto torque_at = [&](double t, Eigen::VectorXd& out) {
        const double s = std::clamp((t - control_time) / control_period, 0.0, 1.0);
        out = u_prev + s * (u_cur - u_prev);
    };
    // A state that is no longer finite ends the run here, at its time and joint, before the model sees it
    // (no nan rows, no internal error from the dynamics).
    auto accelerations = [&](double t, const Eigen::VectorXd& qs, const Eigen::VectorXd& qds, const Eigen::VectorXd& u, Eigen::VectorXd& qdd) {
        require_finite_state(t, {{"position", &qs}, {"velocity", &qds}, {"torque", &u}}, kDivergence);
        if (!dynamics.accelerations(qs.data(), qds.data(), u.data(), qdd.data())) throw InputError(failure);
        require_finite_state(t, {{"acceleration", &qdd}}, kDivergence);
    };
    Eigen::VectorXd k_q[4], k_qd[4];
    for (int i = 0; i < 4; ++i) {
        k_q[i].resize(n);
        k_qd[i].resize(n);
    }
    Eigen::VectorXd q_stage(n), qd_stage(n), tau_stage(n), tau(n), qdd(n), q_before(n);
    Eigen::VectorXd held = Eigen::VectorXd::Zero(n);  // friction with memory, over the current step
    Eigen::VectorXd external = Eigen::VectorXd::Zero(n), external_stage = Eigen::VectorXd::Zero(n);
    auto derivative = [&](double t, const Eigen::VectorXd& qs, const Eigen::VectorXd& qds, Eigen::VectorXd& dq, Eigen::VectorXd& dqd) {
        torque_at(t, tau_stage);
        tau_stage -= held;
        if (settings.external) {
            settings.external(t, external_stage);
            tau_stage += external_stage;
        }
        dq = qds;
        accelerations(t, qs, qds, tau_stage, dqd);
    };

    ClosedLoopSample sample;
    sample.q = &q;
    sample.qd = &qd;
    sample.qdd = &qdd;
    sample.tau = &tau;
    sample.reference = &ref;
    sample.external = &external;
    for (std::size_t step = 0;; ++step) {
        const double t = static_cast<double>(step) * h;
        if (step % static_cast<std::size_t>(settings.substeps) == 0) {
            reference(t, ref);
            u_prev = u_cur;
            control_time = t;
            for (Eigen::Index j = 0; j < n; ++j) {
                const auto js = static_cast<std::size_t>(j);
                u_cur[j] = gains.kp[j] * (ref.q[js] - q[j]) + gains.kd[j] * (ref.qd[js] - qd[j]);
            }
        }
        if (step % settings.steps_per_output == 0) {
            torque_at(t, tau);
            if (settings.external) settings.external(t, external);
            accelerations(t, q, qd, tau - held + external, qdd);
            sample.index = step / settings.steps_per_output;
            sample.t = t;
            sink(sample);
        }
        if (step >= total_steps) break;
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
        q_before = q;
        q += h / 6.0 * (k_q[0] + 2.0 * k_q[1] + 2.0 * k_q[2] + k_q[3]);
        qd += h / 6.0 * (k_qd[0] + 2.0 * k_qd[1] + 2.0 * k_qd[2] + k_qd[3]);
        if (friction) friction->step(q_before, q, held);
    }
}

}  // namespace jacobid::sim
