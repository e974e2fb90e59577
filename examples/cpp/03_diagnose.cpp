// SPDX-License-Identifier: MIT
// 03: model-discrepancy diagnosis from code (docs/diagnose.md). The simulated 2R robot carries a constant
// 0.2 N.m friction offset on joint 1 that the nominal model lacks; the diagnosis must name it and size it.
#include <jacobid/host.hpp>

#include <cmath>
#include <cstdio>

int main() try {
    using namespace jacobid;
    const robot::RobotDescription robot = robot::default_planar2r_description();
    const auto nominal = robot::make_robot_model(robot);
    const sim::EffectContext context{nominal->model_name(), nominal->joint_count(), robot.coulomb, robot::joint_coulomb_signs(robot)};

    // The truth: the nominal model plus the hidden effect's column, with its injected coefficient.
    const sim::EffectSpec hidden = sim::parse_effect("coulomb_offset:joint=1,value=0.2", nominal->joint_count());
    const sim::AugmentedModel truth_model(*nominal, context, {sim::term_of(hidden)});
    const Eigen::VectorXd x_nominal = robot::true_parameters(robot, *nominal);
    Eigen::VectorXd x_truth(truth_model.parameter_count());
    x_truth << x_nominal, sim::injected_coefficients(hidden, *nominal, x_nominal);

    sim::SimulationSettings simulation;
    simulation.duration = 40.0;
    sim::MeasurementSettings sensors;
    sensors.torque_noise = {0.05, 0.01};
    sim::MeasurementModel measurement(sensors);
    const sim::MeasuredLog simulated = sim::simulate_log(truth_model, x_truth, robot.joints, simulation, measurement);

    // Diagnose the nominal model against the log (no validation log: blocked cross-validation).
    const identify::LogColumns log = identify::log_columns(simulated.q, simulated.tau, simulated.sample_period, "simulated 2R with an offset");
    const diagnose::Diagnosis d = diagnose::run_diagnosis(*nominal, context, log, nullptr, diagnose::DiagnoseSettings{},
                                                          [](const std::string& line) { std::printf("  %s\n", line.c_str()); });
    bool found = false;
    for (const auto& e : d.effects) {
        std::printf("named %s: %.3f +- %.3f %s\n", e.term.label().c_str(), e.value, e.std, sim::effect_unit(e.term.kind));
        found = found || (e.term.kind == sim::EffectKind::CoulombOffset && e.term.joint == 0 && std::abs(e.value - 0.2) < 0.03);
    }
    std::printf("held-out error before %.4f, after %.4f (in units of the joints' noise)\n", d.before.heldout_weighted, d.after.heldout_weighted);
    return found && d.after.heldout_weighted < d.before.heldout_weighted ? 0 : 1;
} catch (const jacobid::InputError& e) {
    std::printf("error: %s\n", e.what());
    return 2;
}
