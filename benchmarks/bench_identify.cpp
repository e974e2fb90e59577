// SPDX-License-Identifier: MIT
// One hour of 1 kHz 2R data (3.6 M samples) identified end to end, with the split of the time between
// parsing, differentiation, regressor + decimation filter, and least squares, and the peak RSS.
//
// Usage: bench_identify LOG.csv [--generate SECONDS]
//   --generate: first simulate LOG.csv (default 3600 s, 1 kHz, encoder 2^16, noise 0.05 / 0.01 N.m).
// The CLI equivalent (`/usr/bin/time -v jacobid identify --robot r.yaml --in LOG.csv`) measures the same
// pipeline plus process start-up; docs/performance.md records both.
#include <fmt/core.h>
#include <sys/resource.h>

#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "identify/solve/least_squares.hpp"
#include "identify/pipeline/pipeline.hpp"
#include "io/csv_table.hpp"
#include "io/time_axis.hpp"
#include "robot/planar2r_model.hpp"
#include "robot/robot_description.hpp"
#include "sim/simulator.hpp"

namespace {

double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

void generate(const std::string& path, double seconds) {
    const auto robot = jacobid::robot::default_planar2r_description();
    const auto model = jacobid::robot::make_robot_model(robot);
    const auto table = jacobid::robot::paper_table2_parameters(dynamic_cast<const jacobid::robot::Planar2RModel&>(*model));
    const Eigen::VectorXd x = Eigen::Map<const Eigen::VectorXd>(table.data(), static_cast<Eigen::Index>(table.size()));
    jacobid::sim::SimulationSettings settings;
    settings.duration = seconds;
    jacobid::sim::MeasurementSettings ms;
    ms.torque_noise = {0.05, 0.01};
    jacobid::sim::MeasurementModel measurement(ms);
    std::ofstream out(path);
    out << "t,q1,q2,tau1,tau2\n";
    std::size_t k = 0;
    jacobid::sim::simulate(*model, x, robot.joints, settings, measurement, [&](const jacobid::sim::SimulatedSample& s) {
        out << fmt::format("{:.6f},{:.12g},{:.12g},{:.10g},{:.10g}\n", static_cast<double>(k++) * 1e-3, s.q_measured[0], s.q_measured[1],
                           s.tau_measured[0], s.tau_measured[1]);
    });
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        fmt::print(stderr, "usage: bench_identify LOG.csv [--generate SECONDS]\n");
        return 2;
    }
    const std::string path = argv[1];
    if (argc >= 3 && std::strcmp(argv[2], "--generate") == 0) {
        const double seconds = argc >= 4 ? std::stod(argv[3]) : 3600.0;
        const double t0 = now();
        generate(path, seconds);
        fmt::print("generated {} ({} s of 1 kHz data) in {:.1f} s\n", path, seconds, now() - t0);
    }
    try {
        const auto robot = jacobid::robot::default_planar2r_description();
        const auto model = jacobid::robot::make_robot_model(robot);
        const double t0 = now();
        const jacobid::io::CsvTable table = jacobid::io::read_csv(path);
        jacobid::identify::LogColumns log;
        log.source = path;
        const auto axis = jacobid::io::check_uniform_time(table, "t");
        log.sample_period = axis.sample_period;
        for (const auto& j : robot.joints) log.q.push_back(&table.column(j.position_column));
        for (const auto& j : robot.joints) log.tau.push_back(&table.column(j.torque_column));
        const double t1 = now();
        jacobid::identify::PipelineSettings settings;
        const auto out = jacobid::identify::run_pipeline(*model, log, settings);
        const double t2 = now();
        const auto solution = jacobid::identify::solve_least_squares(out.factors, model->parameter_names());
        const double t3 = now();
        rusage usage{};
        getrusage(RUSAGE_SELF, &usage);
        fmt::print("samples {}  equations {}  relative error norm {:.4g} %\n", log.samples(), solution.equations, 100 * solution.relative_error_norm);
        fmt::print("parse + time check  {:7.3f} s\n", t1 - t0);
        fmt::print("plan (bandwidth, windows) {:7.3f} s\n", (t2 - t1) - out.info.seconds_differentiate - out.info.seconds_regressor_filter - out.info.seconds_ls);
        fmt::print("differentiate       {:7.3f} s\n", out.info.seconds_differentiate);
        fmt::print("regressor + F_p     {:7.3f} s\n", out.info.seconds_regressor_filter);
        fmt::print("LS (running QR)     {:7.3f} s  (+ solve/statistics {:.3f} s)\n", out.info.seconds_ls, t3 - t2);
        fmt::print("total               {:7.3f} s\n", t3 - t0);
        fmt::print("peak RSS            {:7.1f} MB\n", static_cast<double>(usage.ru_maxrss) / 1024.0);
        for (std::size_t p = 0; p < solution.names.size(); ++p) fmt::print("  {:<5} {:.6g}\n", solution.names[p], solution.x[static_cast<Eigen::Index>(p)]);
    } catch (const std::exception& e) {
        fmt::print(stderr, "bench_identify: {}\n", e.what());
        return 2;
    }
    return 0;
}
