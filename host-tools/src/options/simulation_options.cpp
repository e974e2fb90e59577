// SPDX-License-Identifier: MIT
#include "options/simulation_options.hpp"

#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include <cmath>

#include "options/option_checks.hpp"
#include "core/errors.hpp"
#include "robot/robot_description.hpp"

namespace jacobid::options {
namespace {

// Simulated logs beyond these sizes are typos (--duration 1e12), not experiments: a billion log samples is
// about 100 GB of CSV, ten billion RK4 steps hours of computing.
constexpr double kMaxLogSamples = 1e9;
constexpr double kMaxIntegrationSteps = 1e10;
// N.m: far above any drive's torque, and its squares stay finite in the noise and ripple models.
constexpr double kMaxTorqueAmplitude = 1e6;

}  // namespace

void add_simulation_options(CLI::App* cmd, SimulationOptions& o) {
    cmd->add_option("--duration", o.settings.duration, "simulated time in s")->check(positive_number())->capture_default_str();
    cmd->add_option("--rate", o.settings.output_rate, "log sample rate in Hz (must divide the integration rate)")->check(positive_number())->capture_default_str();
    const char* described = " (a robot description's controller: replaces it)";
    o.controller_options = {
        cmd->add_option("--control-rate", o.settings.control_rate, std::string("PD controller rate in Hz") + described)
            ->check(positive_number())
            ->capture_default_str(),
        cmd->add_option("--substeps", o.settings.substeps, std::string("RK4 steps per control period") + described)
            ->check(whole_number_from(1))
            ->capture_default_str(),
        cmd->add_option("--omega-dyn", o.settings.omega_dyn, std::string("wanted position-loop bandwidth in rad/s (sets the PD gains)") + described)
            ->check(positive_number())
            ->capture_default_str(),
        cmd->add_option("--damping", o.settings.damping, std::string("damping ratio of the PD loop") + described)->check(positive_number())->capture_default_str()};
    cmd->add_option("--seed", o.settings.seed, "seed of the random targets and move durations")->check(whole_number_from(0))->capture_default_str();
    cmd->add_option("--move-duration", o.move_duration, "MIN,MAX duration of each move in s")
        ->delimiter(',')
        ->expected(2)
        ->check(positive_number())
        ->capture_default_str();
    cmd->add_option("--velocity-limit", o.settings.moves.velocity_limit,
                    "rad/s: the random moves' reference stays within it (a move lasts as long as its largest step needs); one value or one "
                    "per joint (default: none)")
        ->delimiter(',')
        ->check(positive_number());
    cmd->add_option("--acceleration-limit", o.settings.moves.acceleration_limit,
                    "rad/s^2: the random moves' reference stays within it; one value or one per joint (default: none)")
        ->delimiter(',')
        ->check(positive_number());
    cmd->add_option("--dwell", o.settings.moves.max_dwell, "maximum rest after each move in s (uniform in [0, dwell])")
        ->check(non_negative_number())
        ->capture_default_str();
    cmd->add_option("--encoder-counts", o.encoder_counts, "encoder counts per revolution (0: no quantization)")->check(non_negative_number())->capture_default_str();
    cmd->add_option("--position-noise", o.position_noise,
                    "standard deviation in rad of white noise on the logged positions (before the encoder quantization; own seed stream)")
        ->check(non_negative_number())
        ->capture_default_str();
    add_torque_noise_option(cmd, o.torque_noise);
    cmd->add_option("--ripple", o.ripple, "torque ripple amplitude in N.m (one value or one per joint), amplitude * sin(periods * q)")
        ->delimiter(',')
        ->check(number_in(0.0, kMaxTorqueAmplitude));
    cmd->add_option("--ripple-periods", o.ripple_periods, "ripple periods per revolution")->check(non_negative_number())->capture_default_str();
    add_noise_seed_option(cmd, o.noise_seed);
}

void add_torque_noise_option(CLI::App* cmd, std::vector<double>& torque_noise) {
    cmd->add_option("--torque-noise", torque_noise, "torque noise standard deviation in N.m: one value or one per joint")
        ->delimiter(',')
        ->check(number_in(0.0, kMaxTorqueAmplitude));
}

void add_noise_seed_option(CLI::App* cmd, std::uint64_t& noise_seed) {
    cmd->add_option("--noise-seed", noise_seed, "seed of the torque noise")->check(whole_number_from(0))->capture_default_str();
}

void refuse_oversized_simulation(const sim::SimulationSettings& s, double bytes_per_sample) {
    const double samples = std::floor(s.duration * s.output_rate) + 1.0;
    refuse_oversized(fmt::format("--duration {:g} s at --rate {:g} Hz", s.duration, s.output_rate), samples, kMaxLogSamples, "log samples",
                     bytes_per_sample, "lower --duration or --rate");
    const double steps = s.duration * s.control_rate * static_cast<double>(s.substeps);
    refuse_oversized(fmt::format("--duration {:g} s at --control-rate {:g} Hz x --substeps {}", s.duration, s.control_rate, s.substeps), steps,
                     kMaxIntegrationSteps, "integration steps", 0.0, "lower --duration, --control-rate or --substeps");
}

void apply_controller(const robot::RobotDescription& description, SimulationOptions& o) {
    if (!description.controller) return;
    for (const CLI::Option* option : o.controller_options) {
        if (option->count() > 0) {
            throw InputError(fmt::format("{} and {}'s controller: give the controller in one place", option->get_name(), description.source));
        }
    }
    const robot::ControllerDescription& c = *description.controller;
    o.settings.control_rate = c.rate;
    o.settings.substeps = c.substeps;
    if (c.kp.empty()) {
        o.settings.omega_dyn = c.omega;
        o.settings.damping = c.damping;
    } else {
        o.settings.kp = Eigen::Map<const Eigen::VectorXd>(c.kp.data(), static_cast<Eigen::Index>(c.kp.size()));
        o.settings.kd = Eigen::Map<const Eigen::VectorXd>(c.kd.data(), static_cast<Eigen::Index>(c.kd.size()));
    }
}

sim::SimulationSettings simulation_settings(const SimulationOptions& o) {
    sim::SimulationSettings s = o.settings;
    if (o.move_duration.size() != 2) throw InputError("--move-duration: expected MIN,MAX in seconds");
    s.moves.min_duration = o.move_duration[0];
    s.moves.max_duration = o.move_duration[1];
    sim::validate(s);
    return s;
}

sim::MeasurementSettings measurement_settings(const SimulationOptions& o, int joints) {
    const auto n = static_cast<std::size_t>(joints);
    auto per_joint = [&](const std::vector<double>& v, const char* option) {
        if (v.empty()) return std::vector<double>(n, 0.0);
        if (v.size() == 1) return std::vector<double>(n, v[0]);
        if (v.size() != n) throw InputError(fmt::format("{}: expected 1 or {} values (one per joint), got {}", option, n, v.size()));
        for (double a : v) {
            if (!(a >= 0.0)) throw InputError(fmt::format("{}: values must be >= 0", option));
        }
        return v;
    };
    sim::MeasurementSettings ms;
    if (o.encoder_counts < 0.0) throw InputError("--encoder-counts must be >= 0 (0: no quantization)");
    ms.encoder_counts_per_rev = o.encoder_counts;
    ms.torque_noise = per_joint(o.torque_noise, "--torque-noise");
    ms.ripple_amplitude = per_joint(o.ripple, "--ripple");
    ms.ripple_periods_per_rev = o.ripple_periods;
    if (!(o.position_noise >= 0.0) || !std::isfinite(o.position_noise)) throw InputError("--position-noise must be >= 0 rad");
    ms.position_noise = o.position_noise;
    ms.seed = o.noise_seed;
    return ms;
}

}  // namespace jacobid::options
