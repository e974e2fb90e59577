// SPDX-License-Identifier: MIT
#include "identify/solve/reference_simulation.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "core/errors.hpp"
#include "sim/closed_loop.hpp"
#include "sim/dahl_friction.hpp"

namespace jacobid::identify {

void require_reference_simulation(const LogColumns& log, const robot::RobotDescription& description, const std::string& estimator) {
    for (std::size_t j = 0; j < log.q.size(); ++j) {
        for (auto [name, list] : {std::pair{"q_ref", &log.q_ref}, std::pair{"qd_ref", &log.qd_ref}}) {
            if (j >= list->size() || !(*list)[j]) {
                throw InputError(fmt::format("--estimator {}: {} has no reference {}{} (columns q_refJ and qd_refJ, as jacobid simulate writes them, "
                                             "or references: in --log-format)",
                                             estimator, log.source, name, j + 1));
            }
            if ((*list)[j]->size() != log.samples()) {
                throw InputError(fmt::format("--estimator {}: {}: reference {}{} has {} samples, the positions {}", estimator, log.source, name, j + 1,
                                             (*list)[j]->size(), log.samples()));
            }
        }
    }
    if (!description.controller) {
        throw InputError(fmt::format("--estimator {}: {} has no controller (e.g. controller: {{kp: [...], kd: [...], rate: 1000}} or "
                                     "{{omega: 30, damping: 1, rate: 1000}}) to simulate the identified model with",
                                     estimator, description.source));
    }
}

StateEstimates simulate_along_reference(const robot::RobotModel& model, const Eigen::VectorXd& x, const robot::RobotDescription& description,
                                        const robot::RobotModel& nominal, const LogColumns& log, const PipelineInfo& info) {
    const robot::ControllerDescription& controller = *description.controller;
    const std::size_t n = log.samples();
    const std::size_t joints = log.q.size();
    const double ts = log.sample_period;
    sim::ClosedLoopSettings loop;
    loop.control_rate = controller.rate;
    loop.substeps = controller.substeps;
    const double steps = controller.rate * controller.substeps * ts;
    if (steps < 1.0 - 1e-9 || std::abs(steps - std::round(steps)) > 1e-6 * steps) {
        throw InputError(fmt::format("{}: sample period {} s is not a whole number of simulation steps (controller rate {} Hz x substeps {})",
                                     log.source, ts, controller.rate, controller.substeps));
    }
    loop.steps_per_output = static_cast<std::size_t>(std::llround(steps));
    loop.samples = n;

    robot::ForwardDynamics truth(nominal, robot::true_parameters(description, nominal));
    const sim::PdGains gains = sim::described_gains(controller, truth, description.joints);

    // The logged reference at time t (from the log's first sample), linear between samples.
    auto reference = [&](double t, sim::ReferenceSample& out) {
        const double k = std::clamp(t / ts, 0.0, static_cast<double>(n - 1));
        const auto k0 = std::min(static_cast<std::size_t>(k), n - 1);
        const std::size_t k1 = std::min(k0 + 1, n - 1);
        const double a = k - static_cast<double>(k0);
        out.q.resize(joints);
        out.qd.resize(joints);
        for (std::size_t j = 0; j < joints; ++j) {
            out.q[j] = (1.0 - a) * (*log.q_ref[j])[k0] + a * (*log.q_ref[j])[k1];
            out.qd[j] = (1.0 - a) * (*log.qd_ref[j])[k0] + a * (*log.qd_ref[j])[k1];
        }
    };
    Eigen::VectorXd q0(static_cast<Eigen::Index>(joints)), qd0(static_cast<Eigen::Index>(joints));
    for (std::size_t j = 0; j < joints; ++j) {
        q0[static_cast<Eigen::Index>(j)] = log.q_ref[j]->front();
        qd0[static_cast<Eigen::Index>(j)] = log.qd_ref[j]->front();
    }

    StateEstimates e;
    e.first = info.first;
    e.last = info.last;
    e.q.assign(joints, std::vector<double>(n, 0.0));
    e.qd = e.q;
    e.qdd = e.q;
    for (std::size_t j = 0; j < joints; ++j) e.tau.push_back(*log.tau[j]);
    robot::ForwardDynamics dynamics(model, x);
    // A model with presliding friction holds FDj s_j along the simulated path, as `simulate` does (the states
    // start at 0, as the identification's do): without it the simulated motion lacked the held friction the
    // identified FDj stand for, and the instruments or DIDIM's residual carried it.
    const std::unique_ptr<sim::DahlFriction> dahl = sim::presliding_friction(model, x);
    sim::run_closed_loop(dynamics, q0, qd0, gains, loop, reference,
                         fmt::format("{}: the identified parameters give an inertia matrix that is not positive definite: the model cannot be simulated "
                                     "along the reference",
                                     log.source),
                         [&](const sim::ClosedLoopSample& s) {
                             for (std::size_t j = 0; j < joints; ++j) {
                                 const auto jj = static_cast<Eigen::Index>(j);
                                 e.q[j][s.index] = (*s.q)[jj];
                                 e.qd[j][s.index] = (*s.qd)[jj];
                                 e.qdd[j][s.index] = (*s.qdd)[jj];
                             }
                         },
                         dahl.get());
    return e;
}

}  // namespace jacobid::identify
