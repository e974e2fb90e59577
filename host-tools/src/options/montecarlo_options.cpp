// SPDX-License-Identifier: MIT
#include "options/montecarlo_options.hpp"

#include <fmt/core.h>

#include <thread>

#include "core/errors.hpp"
#include "options/option_checks.hpp"
#include "robot/robot_description.hpp"

namespace jacobid::options {

void add_montecarlo_options(CLI::App* cmd, MonteCarloOptions& o) {
    o.settings.seed = 100;
    o.noise_seed = 500;
    cmd->add_option("--runs", o.runs, "number of simulated runs")->capture_default_str();  // >= 2: checked by the study (montecarlo/study.cpp)
    cmd->add_option("--threads", o.threads, "worker threads (0: one per core); the results do not depend on it")
        ->check(whole_number_from(0))
        ->capture_default_str();
    cmd->add_option("--method", o.method, "jacobi, butterworth, or both")->check(CLI::IsMember({"jacobi", "butterworth", "both"}))->capture_default_str();
    add_simulation_options(cmd, o);
    cmd->get_option("--seed")->description("trajectory seed of the first run; run k (from 0) uses SEED + k");
    cmd->get_option("--noise-seed")->description("torque-noise seed of the first run; run k uses NOISE_SEED + k");
    add_fit_options(cmd, o);
    cmd->add_flag("--quiet", o.quiet, "no progress messages on stderr");
}

montecarlo::StudySettings study_settings(const MonteCarloOptions& o) {
    montecarlo::StudySettings s;
    s.robot = o.robot.empty() ? robot::default_planar2r_description() : robot::load_robot_description(o.robot);
    SimulationOptions simulation = o;  // the description's controller, if any
    apply_controller(s.robot, simulation);
    s.simulation = simulation_settings(simulation);
    // Each run holds its log in memory: positions, torques and references as doubles.
    refuse_oversized_simulation(s.simulation, 32.0 * static_cast<double>(s.robot.joints.size()));
    s.measurement = measurement_settings(o, static_cast<int>(s.robot.joints.size()));
    for (const identify::Method m : methods_of(o.method)) s.methods.push_back(identify_settings(o, m));
    s.runs = o.runs;
    if (o.threads < 0) throw InputError(fmt::format("--threads {}: must be >= 0 (0: one per core)", o.threads));
    s.threads = o.threads > 0 ? o.threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    return s;
}

montecarlo::StudyContext study_context(const MonteCarloOptions& o, const montecarlo::StudySettings& s) {
    montecarlo::StudyContext c;
    c.robot = o.robot.empty() ? "built-in planar2r" : o.robot;
    const sim::SimulationSettings& sim = s.simulation;
    const sim::MeasurementSettings& ms = s.measurement;
    // As identify_settings resolved them (--estimator ols | wls is the weighting by another name).
    const std::string weighting = s.methods.front().solve.weighted ? "wls" : "ols";
    const std::string estimator = identify::to_string(s.methods.front().estimator.estimator);
    c.settings = {{"runs", o.runs},
                  {"seed", sim.seed},
                  {"noise_seed", ms.seed},
                  {"method", o.method},
                  {"simulation", {{"duration", sim.duration}, {"rate", sim.output_rate}, {"control_rate", sim.control_rate},
                                  {"substeps", sim.substeps}, {"omega_dyn", sim.omega_dyn}, {"damping", sim.damping},
                                  {"move_duration", o.move_duration}, {"dwell", sim.moves.max_dwell}}},
                  {"measurement", {{"encoder_counts_per_rev", ms.encoder_counts_per_rev}, {"torque_noise", ms.torque_noise},
                                   {"ripple_amplitude", ms.ripple_amplitude}, {"ripple_periods_per_rev", ms.ripple_periods_per_rev},
                                   {"position_noise", ms.position_noise}}},
                  {"identify", {{"estimator", estimator}, {"weighting", weighting}, {"weighted", weighting == "wls"}, {"std_method", o.std_method}, {"torque_delay", o.torque_delay}, {"discretization", o.discretization},
                                {"bandwidth", o.pipeline.bandwidth}, {"cutoff", o.pipeline.differentiator_cutoff},
                                {"decimation_cutoff", o.pipeline.decimation_cutoff}, {"decimation", o.pipeline.decimation},
                                {"coulomb_velocity_ratio", o.pipeline.coulomb_velocity_ratio}}}};
    std::string noise;
    for (double v : ms.torque_noise) noise += fmt::format("{}{:g}", noise.empty() ? "" : "/", v);
    c.settings_line = fmt::format("{} runs (seeds {}..{}, noise seeds {}..{}), {:g} s at {:g} Hz, torque noise {} N.m{}", o.runs, sim.seed,
                                  sim.seed + static_cast<std::uint64_t>(o.runs) - 1, ms.seed, ms.seed + static_cast<std::uint64_t>(o.runs) - 1,
                                  sim.duration, sim.output_rate, noise, weighting == "wls" ? ", weighted LS" : ", ordinary LS") +
                       (ms.position_noise > 0.0 ? fmt::format(", position noise {:g} rad", ms.position_noise) : std::string()) +
                       (estimator == "iv" || estimator == "didim" ? ", then estimator " + estimator : std::string());
    return c;
}

}  // namespace jacobid::options
