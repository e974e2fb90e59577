// SPDX-License-Identifier: MIT
#pragma once
// A Monte Carlo study of the identification (jacobid montecarlo, docs/montecarlo.md): N simulated runs of
// one robot description, run k with trajectory seed seed + k and noise seed noise_seed + k, each identified
// by every method as `jacobid identify` would (identify_run.hpp), the estimates kept against the truth.
// Runs are independent and spread over threads; each run's numbers depend on its seeds alone, so the result
// is the same for any thread count.
#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "identify/identify_run.hpp"
#include "robot/robot_description.hpp"
#include "sim/measurement.hpp"
#include "sim/simulator.hpp"

namespace jacobid::montecarlo {

struct StudySettings {
    robot::RobotDescription robot;
    sim::SimulationSettings simulation;    // simulation.seed: run 0's trajectory seed
    sim::MeasurementSettings measurement;  // measurement.seed: run 0's noise seed
    std::vector<identify::IdentifySettings> methods;
    int runs = 40;
    int threads = 1;
    // Called after each finished run with the number finished so far (serialized, from any thread).
    std::function<void(int finished, int runs)> progress;
};

// One method's estimates, run by run (NaN where a parameter was not identified).
struct MethodRuns {
    identify::Method method = identify::Method::Jacobi;
    std::vector<Eigen::VectorXd> x, std_dev;
};

struct Study {
    std::string model_name;
    std::vector<std::string> names;  // base parameters, model order
    Eigen::VectorXd truth;           // what the simulator used (simulate's truth JSON "parameters")
    std::vector<std::uint64_t> seeds, noise_seeds;  // per run
    std::vector<MethodRuns> methods;
    double seconds = 0.0;  // wall time of the runs
    int threads = 1;
};

// The seeds of run k.
std::uint64_t run_seed(const StudySettings& settings, int k);
std::uint64_t run_noise_seed(const StudySettings& settings, int k);

// One run's estimates, per method (NaN where a parameter was not identified).
struct RunEstimates {
    std::vector<Eigen::VectorXd> x, std_dev;
};

// Run k (from 0) alone: its simulation and identifications, the same numbers wherever it runs (a thread of
// run_study, a Dask task of jacobid.fleet.montecarlo). Its error prefixed with the run and its seeds.
RunEstimates run_one(const StudySettings& settings, int k);

// The study of the runs 0 .. runs.size() - 1 (`seconds` of wall time on `threads` threads or workers).
// InputError for fewer than 2 runs or no method.
Study collect_study(const StudySettings& settings, std::vector<RunEstimates> runs, double seconds, int threads);

// Runs the study. InputError for runs < 2 or threads < 1, or a failing run's error prefixed with the run and
// its seeds (the lowest run index among those that failed before the workers stopped taking new runs).
Study run_study(const StudySettings& settings);

}  // namespace jacobid::montecarlo
