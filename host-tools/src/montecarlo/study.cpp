// SPDX-License-Identifier: MIT
#include "montecarlo/study.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <exception>
#include <limits>
#include <stdexcept>

#include "core/errors.hpp"
#include "core/parallel_for.hpp"
#include "identify/plan/log_columns.hpp"
#include "robot/simulated_parameters.hpp"

namespace jacobid::montecarlo {
namespace {

void check_study(const StudySettings& s) {
    if (s.runs < 2) throw InputError(fmt::format("--runs {}: need at least 2 runs (the spread of the estimates needs two)", s.runs));
    if (s.methods.empty()) throw InputError("--method: no method to identify with");
}

// One run: simulate_log is what `jacobid simulate` writes (without the CSV's rounding), identify_log what
// `jacobid identify` does with it.
RunEstimates simulate_and_identify(const StudySettings& s, const robot::RobotModel& model, const Eigen::VectorXd& truth, int k) {
    sim::SimulationSettings simulation = s.simulation;
    simulation.seed = run_seed(s, k);
    sim::MeasurementSettings sensors = s.measurement;
    sensors.seed = run_noise_seed(s, k);
    sim::MeasurementModel measurement(sensors);
    const sim::MeasuredLog simulated = sim::simulate_log(model, truth, s.robot.joints, simulation, measurement);
    identify::LogColumns log = identify::log_columns(simulated.q, simulated.tau, simulated.sample_period, fmt::format("run {}", k + 1));
    for (std::size_t j = 0; j < simulated.q_ref.size(); ++j) {
        log.q_ref.push_back(&simulated.q_ref[j]);
        log.qd_ref.push_back(&simulated.qd_ref[j]);
    }
    RunEstimates r;
    for (const auto& method : s.methods) {
        const identify::IdentifiedLog fit = identify::identify_log(s.robot, model, log, method);
        if (fit.result.solution.names != model.parameter_names()) {
            throw std::logic_error("montecarlo: the fitted model's parameters differ from the description's");
        }
        r.x.push_back(fit.result.solution.x);
        r.std_dev.push_back(fit.result.solution.std_dev);
    }
    return r;
}

// Run k on the study's model, its error prefixed with the run and its seeds.
RunEstimates checked_run(const StudySettings& s, const robot::RobotModel& model, const Eigen::VectorXd& truth, int k) {
    const auto where = [&] { return fmt::format("run {} (seed {}, noise seed {})", k + 1, run_seed(s, k), run_noise_seed(s, k)); };
    try {
        return simulate_and_identify(s, model, truth, k);
    } catch (const InputError& e) {
        throw InputError(fmt::format("{}: {}", where(), e.what()));
    } catch (const std::exception& e) {
        // Not the user's input: still say which run, so that it can be reproduced with simulate + identify.
        throw std::runtime_error(fmt::format("{}: {}", where(), e.what()));
    }
}

}  // namespace

std::uint64_t run_seed(const StudySettings& settings, int k) { return settings.simulation.seed + static_cast<std::uint64_t>(k); }
std::uint64_t run_noise_seed(const StudySettings& settings, int k) { return settings.measurement.seed + static_cast<std::uint64_t>(k); }

RunEstimates run_one(const StudySettings& s, int k) {
    const auto model = robot::make_robot_model(s.robot);
    return checked_run(s, *model, robot::simulated_parameters(s.robot, *model), k);
}

Study collect_study(const StudySettings& s, std::vector<RunEstimates> results, double seconds, int threads) {
    check_study(s);
    const auto model = robot::make_robot_model(s.robot);
    Study study;
    study.model_name = model->model_name();
    study.names = model->parameter_names();
    study.truth = robot::simulated_parameters(s.robot, *model);
    study.threads = threads;
    for (std::size_t m = 0; m < s.methods.size(); ++m) {
        MethodRuns mr;
        mr.method = s.methods[m].pipeline.method;
        for (auto& r : results) {
            mr.x.push_back(std::move(r.x[m]));
            mr.std_dev.push_back(std::move(r.std_dev[m]));
        }
        study.methods.push_back(std::move(mr));
    }
    for (int k = 0; k < static_cast<int>(results.size()); ++k) {
        study.seeds.push_back(run_seed(s, k));
        study.noise_seeds.push_back(run_noise_seed(s, k));
    }
    study.seconds = seconds;
    return study;
}

Study run_study(const StudySettings& s) {
    check_study(s);
    if (s.threads < 1) throw InputError(fmt::format("--threads {}: must be >= 1", s.threads));
    const auto start = std::chrono::steady_clock::now();
    const auto model = robot::make_robot_model(s.robot);
    const Eigen::VectorXd truth = robot::simulated_parameters(s.robot, *model);
    const auto runs = static_cast<std::size_t>(s.runs);
    const int threads = std::min(s.threads, s.runs);
    std::vector<RunEstimates> results(runs);
    ParallelForOptions pool;
    pool.threads = threads;
    if (s.progress) pool.progress = [&](std::size_t finished, std::size_t) { s.progress(static_cast<int>(finished), s.runs); };
    const std::vector<std::exception_ptr> errors =
        parallel_for(runs, pool, [&](std::size_t k) { results[k] = checked_run(s, *model, truth, static_cast<int>(k)); });
    for (const auto& e : errors) {
        if (e) std::rethrow_exception(e);  // the lowest run that failed
    }
    return collect_study(s, std::move(results), std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), threads);
}

}  // namespace jacobid::montecarlo
