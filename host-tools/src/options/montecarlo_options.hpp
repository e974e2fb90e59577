// SPDX-License-Identifier: MIT
#pragma once
// `jacobid montecarlo`'s options (docs/montecarlo.md), declared once for the command line
// (cli/montecarlo_command.cpp, which adds its files: --format, --output, --report) and the Python module's
// jacobid.fleet.montecarlo (python/src/montecarlo_bindings.cpp), and the study's settings made from them.
#include <CLI/CLI.hpp>
#include <string>

#include "montecarlo/study.hpp"
#include "montecarlo/study_report.hpp"
#include "options/fit_options.hpp"
#include "options/simulation_options.hpp"

namespace jacobid::options {

struct MonteCarloOptions : SimulationOptions, FitOptions {
    std::string robot;
    int runs = 40;
    int threads = 0;  // 0: hardware concurrency
    std::string method = "jacobi";
    bool quiet = false;
};

// --runs, --threads, --method, the simulation's and the fit's options, --quiet (not --robot: a file the caller
// declares). Sets the seeds' defaults (trajectory 100, noise 500).
void add_montecarlo_options(CLI::App* cmd, MonteCarloOptions& o);

// The study's settings: the description (o.robot; empty: the planar 2R) with its controller, the simulation, the
// sensors, one identification per method, --runs and --threads (0: one per core). InputError as the options'.
montecarlo::StudySettings study_settings(const MonteCarloOptions& o);

// What the outputs say about the study's origin (robot, settings, the one-line summary).
montecarlo::StudyContext study_context(const MonteCarloOptions& o, const montecarlo::StudySettings& s);

}  // namespace jacobid::options
