// SPDX-License-Identifier: MIT
// 02: identification from code. Simulate the paper's planar 2R robot (PD control on random quintic moves,
// 2^16-count encoders, noisy torques), then identify its base parameters with the Jacobi pipeline
// (docs/method.md) and compare them with the truth the simulation used (the paper's Table II).
#include <jacobid/host.hpp>

#include <cmath>
#include <cstdio>

int main() try {
    using namespace jacobid;
    const robot::RobotDescription robot = robot::default_planar2r_description();
    const auto model = robot::make_robot_model(robot);
    const Eigen::VectorXd truth = robot::true_parameters(robot, *model);

    // 1. Simulate 40 s at 1 kHz; the log gets what real sensors would give, not the true state.
    sim::SimulationSettings simulation;
    simulation.duration = 40.0;
    sim::MeasurementSettings sensors;
    sensors.torque_noise = {0.05, 0.01};  // N.m per joint
    sim::MeasurementModel measurement(sensors);
    const sim::MeasuredLog simulated = sim::simulate_log(*model, truth, robot.joints, simulation, measurement);

    // 2. Identify: Jacobi derivatives, regressor, parallel decimation, least squares. Bandwidth, windows and
    //    decimation are chosen from the data unless PipelineSettings says otherwise.
    const identify::LogColumns log = identify::log_columns(simulated.q, simulated.tau, simulated.sample_period, "simulated 2R");
    const identify::PipelineOutput out = identify::run_pipeline(*model, log, identify::PipelineSettings{});
    const identify::LsSolution x = identify::solve_least_squares(out.factors, model->parameter_names());
    std::printf("bandwidth %.2f Hz, velocity window %.3f s, decimation %d, %zu equations\n", out.info.bandwidth,
                out.info.velocity_window, out.info.decimation, x.equations);

    // 3. Compare: every estimate within 4 standard deviations (plus 1 % for the differentiators' bias).
    bool ok = x.identified_count == model->parameter_count();
    std::printf("%-6s %9s %9s %9s\n", "param", "truth", "estimate", "2 sigma");
    for (int p = 0; p < model->parameter_count(); ++p) {
        const double error = std::abs(x.x[p] - truth[p]);
        const bool close = error <= 4.0 * x.std_dev[p] + 0.01 * std::abs(truth[p]);
        ok = ok && close;
        std::printf("%-6s %9.4f %9.4f %9.4f%s\n", x.names[p].c_str(), truth[p], x.x[p], 2.0 * x.std_dev[p], close ? "" : "  <- off");
    }
    return ok ? 0 : 1;
} catch (const jacobid::InputError& e) {
    std::printf("error: %s\n", e.what());
    return 2;
}
