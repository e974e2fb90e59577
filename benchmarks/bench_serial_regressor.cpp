// SPDX-License-Identifier: MIT
// Regressor of a 6-axis arm per sample (issue 6, target <= 3 us): the fixed-size RNEA regressor of the
// 78 standard parameters (lib, PUMA 560 with rotor inertia), and the host model's base regressor (52 base
// columns selected from it, what `jacobid identify` evaluates per sample).
// Run: build/benchmarks/bench_serial_regressor --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <random>

#include "jacobid/robot/rnea_regressor.hpp"
#include "robot/robot_description.hpp"
#include "robot/serial_robot_model.hpp"

namespace {

using namespace jacobid::robot;

// The PUMA 560 chain of examples/robots/puma560.yaml.
KinematicChain<6> puma_chain() {
    const auto description = load_robot_description(JACOBID_EXAMPLES_DIR "/robots/puma560.yaml");
    KinematicChain<6> chain;
    for (const auto& joint : description.chain) chain.add(joint);
    return chain;
}

// 1024 random states cycled through, so the branch predictor and caches see realistic variety.
struct States {
    std::vector<RneaRegressor<6>::Joints> q, qd, qdd;
    States() {
        std::mt19937 rng(1);
        std::uniform_real_distribution<double> u(-1.0, 1.0);
        for (int k = 0; k < 1024; ++k) {
            RneaRegressor<6>::Joints a, b, c;
            for (int j = 0; j < 6; ++j) a[j] = 3 * u(rng), b[j] = 2 * u(rng), c[j] = 5 * u(rng);
            q.push_back(a), qd.push_back(b), qdd.push_back(c);
        }
    }
};

void BM_RneaStandardRegressor6(benchmark::State& state) {
    StandardParameterOptions options;
    options.rotor_inertia = true;
    options.coulomb.model = CoulombModel::SmoothAtan;
    const RneaRegressor<6> regressor(puma_chain(), Eigen::Vector3d(0, 0, -9.81), options);
    const States s;
    RneaRegressor<6>::Regressor D;
    std::size_t k = 0;
    for (auto _ : state) {
        regressor.regressor(s.q[k], s.qd[k], s.qdd[k], D);
        benchmark::DoNotOptimize(D.data());
        k = (k + 1) & 1023;
    }
    state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_RneaStandardRegressor6);

void BM_HostBaseRegressorPuma560(benchmark::State& state) {
    const auto description = load_robot_description(JACOBID_EXAMPLES_DIR "/robots/puma560.yaml");
    const auto model = make_robot_model(description);
    const States s;
    Eigen::MatrixXd D(6, model->parameter_count());
    std::size_t k = 0;
    for (auto _ : state) {
        model->regressor(s.q[k].data(), s.qd[k].data(), s.qdd[k].data(), D);
        benchmark::DoNotOptimize(D.data());
        k = (k + 1) & 1023;
    }
    state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_HostBaseRegressorPuma560);

}  // namespace

BENCHMARK_MAIN();
