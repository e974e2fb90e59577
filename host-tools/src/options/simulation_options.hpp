// SPDX-License-Identifier: MIT
#pragma once
// The options of a simulated run (motion, controller, sensors, seeds), registered alike by `jacobid simulate`
// and `jacobid montecarlo`, so that a Monte Carlo run is exactly what simulate would have written.
#include <cstdint>
#include <string>
#include <vector>

#include "sim/measurement.hpp"
#include "sim/simulator.hpp"

namespace CLI {
class App;
class Option;
}  // namespace CLI

namespace jacobid::robot {
struct RobotDescription;
}

namespace jacobid::options {

struct SimulationOptions {
    sim::SimulationSettings settings;
    double encoder_counts = 65536.0;
    std::vector<double> torque_noise;
    std::vector<double> ripple;
    double ripple_periods = 50.0;
    std::uint64_t noise_seed = 2;
    std::vector<double> move_duration{0.6, 1.6};
    double position_noise = 0.0;  // rad
    // --omega-dyn, --damping, --control-rate, --substeps as registered (to tell a given one from its default).
    std::vector<const CLI::Option*> controller_options;
};

// --duration, --rate, --control-rate, --substeps, --omega-dyn, --damping, --seed, --move-duration, --dwell,
// --encoder-counts, --position-noise, --torque-noise, --ripple, --ripple-periods, --noise-seed.
void add_simulation_options(CLI::App* cmd, SimulationOptions& o);

// --torque-noise and --noise-seed alone (sim-can's noise).
void add_torque_noise_option(CLI::App* cmd, std::vector<double>& torque_noise);
void add_noise_seed_option(CLI::App* cmd, std::uint64_t& noise_seed);

// InputError when `s` asks for more than a billion log samples (about `bytes_per_sample` bytes each) or ten
// billion integration steps, naming the options and the estimate; before anything is allocated or run.
void refuse_oversized_simulation(const sim::SimulationSettings& s, double bytes_per_sample);

// The description's controller (robot/controller_description.hpp), if it has one, replaces the controller
// options; InputError if one of them is given as well (two controllers for one run).
void apply_controller(const robot::RobotDescription& description, SimulationOptions& o);

// The checked settings for a robot of `joints` joints (InputError naming the option otherwise).
sim::SimulationSettings simulation_settings(const SimulationOptions& o);
sim::MeasurementSettings measurement_settings(const SimulationOptions& o, int joints);

}  // namespace jacobid::options
