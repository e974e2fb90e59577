// SPDX-License-Identifier: MIT
#include "cli/simulation_options.hpp"

#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include <cmath>

#include "core/errors.hpp"
#include "robot/robot_description.hpp"

namespace jacobid::cli {

void add_simulation_options(CLI::App* cmd, SimulationOptions& o) {
    cmd->add_option("--duration", o.settings.duration, "simulated time in s")->capture_default_str();
    cmd->add_option("--rate", o.settings.output_rate, "log sample rate in Hz (must divide the integration rate)")->capture_default_str();
    const char* described = " (a robot description's controller: replaces it)";
    o.controller_options = {
        cmd->add_option("--control-rate", o.settings.control_rate, std::string("PD controller rate in Hz") + described)->capture_default_str(),
        cmd->add_option("--substeps", o.settings.substeps, std::string("RK4 steps per control period") + described)->capture_default_str(),
        cmd->add_option("--omega-dyn", o.settings.omega_dyn, std::string("wanted position-loop bandwidth in rad/s (sets the PD gains)") + described)
            ->capture_default_str(),
        cmd->add_option("--damping", o.settings.damping, std::string("damping ratio of the PD loop") + described)->capture_default_str()};
    cmd->add_option("--seed", o.settings.seed, "seed of the random targets and move durations")->capture_default_str();
    cmd->add_option("--move-duration", o.move_duration, "MIN,MAX duration of each move in s")->delimiter(',')->expected(2)->capture_default_str();
    cmd->add_option("--dwell", o.settings.moves.max_dwell, "maximum rest after each move in s (uniform in [0, dwell])")->capture_default_str();
    cmd->add_option("--encoder-counts", o.encoder_counts, "encoder counts per revolution (0: no quantization)")->capture_default_str();
    cmd->add_option("--position-noise", o.position_noise,
                    "standard deviation in rad of white noise on the logged positions (before the encoder quantization; own seed stream)")
        ->capture_default_str();
    cmd->add_option("--torque-noise", o.torque_noise, "torque noise standard deviation in N.m: one value or one per joint")->delimiter(',');
    cmd->add_option("--ripple", o.ripple, "torque ripple amplitude in N.m (one value or one per joint), amplitude * sin(periods * q)")
        ->delimiter(',');
    cmd->add_option("--ripple-periods", o.ripple_periods, "ripple periods per revolution")->capture_default_str();
    cmd->add_option("--noise-seed", o.noise_seed, "seed of the torque noise")->capture_default_str();
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

}  // namespace jacobid::cli
