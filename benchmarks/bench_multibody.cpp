// SPDX-License-Identifier: MIT
// Multibody dynamics of the PUMA 560 (examples/robots/puma560.yaml, rotor inertias, its standard
// parameters) per call, ours against orocos-kdl's in one binary (issue 18):
//   inverse dynamics:  lib RneaRegressor<6>::inverse_dynamics      vs KDL ChainIdSolver_RNE
//   regressor:         lib RneaRegressor<6>::regressor (6 x 78)
//   forward dynamics:  lib ArticulatedBody<6>::forward_dynamics   vs KDL ChainFdSolver_RNE
//                      host ForwardDynamics, articulated body (what the simulator calls: friction, copies)
//                      host ForwardDynamics, inertia matrix (the previous route: n + 2 Newton-Euler + LLT)
// KDL is called through tests/unit/robot/kdl_dynamics (compiled without -march, its header says why).
// Run: build/benchmarks/bench_multibody --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <random>

#include "jacobid/robot/articulated_body.hpp"
#include "jacobid/robot/rnea_regressor.hpp"
#include "kdl_links.hpp"
#include "robot/robot_description.hpp"
#include "robot/serial_robot_model.hpp"

namespace {

using namespace jacobid::robot;
using Joints = JointVector<6>;

// The PUMA 560 once: description, host model, the lib chain, the standard parameters.
struct Puma {
    RobotDescription description = load_robot_description(JACOBID_EXAMPLES_DIR "/robots/puma560.yaml");
    SerialRobotConfig config;
    std::unique_ptr<SerialRobotModel> host;
    KinematicChain<6> chain;
    Eigen::VectorXd standard;
    Puma() {
        config.name = description.model;
        config.joints = description.chain;
        config.gravity = description.gravity;
        config.options.coulomb = description.coulomb;
        config.options.rotor_inertia = description.rotor_inertia;
        config.options.friction_offset = description.friction_offset;
        host = std::make_unique<SerialRobotModel>(config);
        for (const auto& joint : description.chain) chain.add(joint);
        standard = standard_values(description, *host);
    }
    RneaRegressor<6>::Parameters lib_parameters() const {
        RneaRegressor<6>::Parameters x = RneaRegressor<6>::Parameters::Zero();
        x.head(standard.size()) = standard;
        return x;
    }
};

const Puma& puma() {
    static const Puma p;
    return p;
}

// 1024 random states cycled through, so the branch predictor and caches see realistic variety; the third
// vector is qdd (inverse dynamics) or tau (forward dynamics).
struct States {
    std::vector<Joints> q, qd, third;
    States() {
        std::mt19937 rng(1);
        std::uniform_real_distribution<double> u(-1.0, 1.0);
        for (int k = 0; k < 1024; ++k) {
            Joints a, b, c;
            for (int j = 0; j < 6; ++j) a[j] = 3 * u(rng), b[j] = 2 * u(rng), c[j] = 5 * u(rng);
            q.push_back(a), qd.push_back(b), third.push_back(c);
        }
    }
};

void BM_RneaInverseDynamicsPuma560(benchmark::State& state) {
    const RneaRegressor<6> rnea(puma().chain, puma().config.gravity, puma().config.options);
    const auto x = puma().lib_parameters();
    const States s;
    Joints tau;
    std::size_t k = 0;
    for (auto _ : state) {
        rnea.inverse_dynamics(s.q[k], s.qd[k], s.third[k], x, tau);
        benchmark::DoNotOptimize(tau.data());
        k = (k + 1) & 1023;
    }
}
BENCHMARK(BM_RneaInverseDynamicsPuma560);

void BM_KdlChainIdSolverRnePuma560(benchmark::State& state) {
    jacobid::test::KdlDynamics kdl(jacobid::test::kdl_links(puma().config, puma().standard), jacobid::test::kdl_gravity(puma().config));
    const States s;
    double tau[6];
    std::size_t k = 0;
    for (auto _ : state) {
        kdl.inverse_dynamics(s.q[k].data(), s.qd[k].data(), s.third[k].data(), tau);
        benchmark::DoNotOptimize(tau);
        k = (k + 1) & 1023;
    }
}
BENCHMARK(BM_KdlChainIdSolverRnePuma560);

void BM_RneaRegressorPuma560(benchmark::State& state) {
    const RneaRegressor<6> rnea(puma().chain, puma().config.gravity, puma().config.options);
    const States s;
    RneaRegressor<6>::Regressor D;
    std::size_t k = 0;
    for (auto _ : state) {
        rnea.regressor(s.q[k], s.qd[k], s.third[k], D);
        benchmark::DoNotOptimize(D.data());
        k = (k + 1) & 1023;
    }
}
BENCHMARK(BM_RneaRegressorPuma560);

void BM_ArticulatedBodyPuma560(benchmark::State& state) {
    ArticulatedBody<6> body(puma().chain, puma().config.gravity);
    body.set_standard_parameters(StandardParameterLayout<6>(6, puma().config.options), puma().standard);
    ArticulatedBody<6>::Data data;
    const States s;
    Joints qdd;
    std::size_t k = 0;
    for (auto _ : state) {
        body.forward_dynamics(s.q[k], s.qd[k], s.third[k], data, qdd);
        benchmark::DoNotOptimize(qdd.data());
        k = (k + 1) & 1023;
    }
}
BENCHMARK(BM_ArticulatedBodyPuma560);

void BM_KdlChainFdSolverRnePuma560(benchmark::State& state) {
    jacobid::test::KdlDynamics kdl(jacobid::test::kdl_links(puma().config, puma().standard), jacobid::test::kdl_gravity(puma().config));
    const States s;
    double qdd[6];
    std::size_t k = 0;
    for (auto _ : state) {
        kdl.forward_dynamics(s.q[k].data(), s.qd[k].data(), s.third[k].data(), qdd);
        benchmark::DoNotOptimize(qdd);
        k = (k + 1) & 1023;
    }
}
BENCHMARK(BM_KdlChainFdSolverRnePuma560);

void host_forward_dynamics(benchmark::State& state, ForwardDynamicsSolver solver) {
    const Eigen::VectorXd x = true_parameters(puma().description, *puma().host);
    ForwardDynamics dynamics(*puma().host, x, solver);
    const States s;
    double qdd[6];
    std::size_t k = 0;
    for (auto _ : state) {
        dynamics.accelerations(s.q[k].data(), s.qd[k].data(), s.third[k].data(), qdd);
        benchmark::DoNotOptimize(qdd);
        k = (k + 1) & 1023;
    }
}
void BM_HostArticulatedBodyPuma560(benchmark::State& state) { host_forward_dynamics(state, ForwardDynamicsSolver::articulated_body); }
BENCHMARK(BM_HostArticulatedBodyPuma560);
void BM_HostInertiaMatrixPuma560(benchmark::State& state) { host_forward_dynamics(state, ForwardDynamicsSolver::inertia_matrix); }
BENCHMARK(BM_HostInertiaMatrixPuma560);

}  // namespace

BENCHMARK_MAIN();
