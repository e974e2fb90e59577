// SPDX-License-Identifier: MIT
// jacobid montecarlo: N simulated runs of a robot description (run k: trajectory seed S + k, noise seed
// S2 + k), each identified as `jacobid identify` would, and per method and parameter the mean error with its
// standard error, the spread of the estimates against the reported std and the coverage of the truth by
// +-2 reported std (docs/montecarlo.md). How users check a setup before spending robot time.
#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include <memory>
#include <thread>

#include "cli/command.hpp"
#include "options/fit_options.hpp"
#include "options/option_checks.hpp"
#include "options/output_file.hpp"
#include "options/robot_files.hpp"
#include "options/simulation_options.hpp"
#include "montecarlo/study.hpp"
#include "montecarlo/study_report.hpp"
#include "robot/robot_description.hpp"

namespace jacobid::cli {
namespace {

struct MonteCarloOptions : SimulationOptions, FitOptions {
    std::string robot;
    int runs = 40;
    int threads = 0;  // 0: hardware concurrency
    std::string method = "jacobi";
    std::string format = "table";
    std::string output = "-";
    std::string report;
    bool quiet = false;
};

std::vector<identify::Method> methods_of(const std::string& method) {
    std::vector<identify::Method> methods;
    if (method == "jacobi" || method == "both") methods.push_back(identify::Method::Jacobi);
    if (method == "butterworth" || method == "both") methods.push_back(identify::Method::Butterworth);
    return methods;
}

montecarlo::StudyContext context_of(const MonteCarloOptions& o, const montecarlo::StudySettings& s) {
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

void run(const MonteCarloOptions& o) {
    montecarlo::StudySettings s;
    s.robot = o.robot.empty() ? robot::default_planar2r_description() : robot::load_robot_description(o.robot);
    std::vector<NamedPath> files = robot_files("--robot", o.robot, s.robot);
    check_outputs({{"--output", o.output}}, files);
    files.push_back({"--output", o.output});
    check_output_directory({"--report", o.report}, files);  // written after the work: checked before it
    SimulationOptions simulation = o;  // the description's controller, if any
    apply_controller(s.robot, simulation);
    s.simulation = simulation_settings(simulation);
    // Each run holds its log in memory: positions, torques and references as doubles.
    refuse_oversized_simulation(s.simulation, 32.0 * static_cast<double>(s.robot.joints.size()));
    s.measurement = measurement_settings(o, static_cast<int>(s.robot.joints.size()));
    for (const identify::Method m : methods_of(o.method)) s.methods.push_back(identify_settings(o, m));
    s.runs = o.runs;
    s.threads = o.threads > 0 ? o.threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    if (o.threads < 0) throw InputError(fmt::format("--threads {}: must be >= 0 (0: one per core)", o.threads));
    if (!o.quiet) s.progress = [](int finished, int runs) { fmt::print(stderr, "run {}/{}\n", finished, runs); };
    const montecarlo::Study study = montecarlo::run_study(s);
    const montecarlo::StudyContext context = context_of(o, s);
    write_output(o.output, o.format == "json" ? montecarlo::to_json(study, context).dump(2) + "\n" : montecarlo::format_table(study, context));
    if (!o.report.empty()) montecarlo::write_report(o.report, study, context);
}

}  // namespace

void add_montecarlo_command(CLI::App& app) {
    auto o = std::make_shared<MonteCarloOptions>();
    o->settings.seed = 100;
    o->noise_seed = 500;
    CLI::App* cmd = app.add_subcommand("montecarlo",
                                       "N simulated runs of a robot (different seeds), each identified as identify would; per method and "
                                       "parameter: mean error and its standard error, spread of the estimates vs the reported std, coverage "
                                       "of the truth by +-2 reported std (docs/montecarlo.md)");
    cmd->add_option("--robot", o->robot, "robot description (YAML); default: planar2r, L1 0.5 m, smoothed Coulomb friction alpha 100 (auto in identification)")->check(file_path());
    cmd->add_option("--runs", o->runs, "number of simulated runs")->capture_default_str();  // >= 2: checked by the study (montecarlo/study.cpp)
    cmd->add_option("--threads", o->threads, "worker threads (0: one per core); the results do not depend on it")
        ->check(whole_number_from(0))
        ->capture_default_str();
    cmd->add_option("--method", o->method, "jacobi, butterworth, or both")->check(CLI::IsMember({"jacobi", "butterworth", "both"}))->capture_default_str();
    cmd->add_option("--format", o->format, "table (text) or json (with every run's estimates)")->check(CLI::IsMember({"table", "json"}))->capture_default_str();
    cmd->add_option("--output,-o", o->output, "output file, '-' for standard output")->capture_default_str()->check(file_path(true));
    cmd->add_option("--report", o->report, "also write DIR/report.md and DIR/montecarlo_<method>.png (normalized errors with the +-2 band)")->check(file_path());
    add_simulation_options(cmd, *o);
    cmd->get_option("--seed")->description("trajectory seed of the first run; run k (from 0) uses SEED + k");
    cmd->get_option("--noise-seed")->description("torque-noise seed of the first run; run k uses NOISE_SEED + k");
    add_fit_options(cmd, *o);
    cmd->add_flag("--quiet", o->quiet, "no progress messages on stderr");
    cmd->callback([o] { run(*o); });
}

}  // namespace jacobid::cli
