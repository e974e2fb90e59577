// SPDX-License-Identifier: MIT
// One controller cycle of contact monitoring at 6 joints (issue 40, docs/monitor.md): the momentum observer's
// step (six Newton-Euler passes: g, p, C qd, two for Mdot qd, plus friction), the direct residual's (one
// pass) and the detector, on the UR5-like arm of examples/robots/ur5_like.yaml with its parameters.
// Run: build/benchmarks/bench_external_torque --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <random>

#include "jacobid/robot/contact_detector.hpp"
#include "jacobid/robot/external_torque.hpp"
#include "robot/robot_description.hpp"
#include "robot/serial_robot_model.hpp"

namespace {

using namespace jacobid::robot;
using Joints = JointVector<6>;

struct Arm {
    RigidBodyTerms<6> terms;
    JointFriction<6> friction;
};

Arm ur5_like() {
    const auto description = load_robot_description(JACOBID_EXAMPLES_DIR "/robots/ur5_like.yaml");
    const auto model = make_robot_model(description);
    const auto& serial = dynamic_cast<const SerialRobotModel&>(*model);
    const auto regressor = make_rnea_regressor<6>(serial.config());
    RneaRegressor<6>::Parameters X = RneaRegressor<6>::Parameters::Zero();
    const Eigen::VectorXd standard = standard_values(description, serial);
    X.head(standard.size()) = standard;
    return {RigidBodyTerms<6>(regressor, X), JointFriction<6>(regressor, X)};
}

struct States {
    std::vector<Joints> q, qd, qdd, tau;
    States() {
        std::mt19937 rng(1);
        std::uniform_real_distribution<double> u(-1.0, 1.0);
        for (int k = 0; k < 1024; ++k) {
            Joints a, b, c, d;
            for (int j = 0; j < 6; ++j) a[j] = 2 * u(rng), b[j] = u(rng), c[j] = 3 * u(rng), d[j] = 20 * u(rng);
            q.push_back(a), qd.push_back(b), qdd.push_back(c), tau.push_back(d);
        }
    }
};

void BM_MomentumObserverAndDetector(benchmark::State& state) {
    const Arm arm = ur5_like();
    MomentumObserver<6> observer(arm.terms, arm.friction, Joints::Constant(100.0), 1e-3);
    ContactDetector<6> detector;
    const States s;
    ExternalTorqueEstimate<6> e;
    std::size_t k = 0;
    for (auto _ : state) {
        observer.step(s.q[k], s.qd[k], s.tau[k], e);
        benchmark::DoNotOptimize(detector.confirmed(detector.detect(e, 6)));
        k = (k + 1) & 1023;
    }
}
BENCHMARK(BM_MomentumObserverAndDetector);

void BM_DirectResidualAndDetector(benchmark::State& state) {
    const Arm arm = ur5_like();
    DirectResidual<6> residual(arm.terms, arm.friction);
    ContactDetector<6> detector;
    const States s;
    ExternalTorqueEstimate<6> e;
    std::size_t k = 0;
    for (auto _ : state) {
        residual.step(s.q[k], s.qd[k], s.qdd[k], s.tau[k], e);
        benchmark::DoNotOptimize(detector.confirmed(detector.detect(e, 6)));
        k = (k + 1) & 1023;
    }
}
BENCHMARK(BM_DirectResidualAndDetector);

}  // namespace

BENCHMARK_MAIN();
