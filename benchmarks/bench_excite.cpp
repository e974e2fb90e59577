// SPDX-License-Identifier: MIT
// One evaluation of `jacobid excite`'s optimizer (docs/excite.md, "Speed" and "Workspace box"): the d-optimal
// criterion with its gradient and the constraints with their Jacobian at a new point (what SLSQP asks per
// iteration), on the PUMA 560 and the UR5-like arm, 5 harmonics at 0.1 Hz, 400 samples per period (the
// default), without (box 0) and with (box 1) a workspace box on the last frame's point, the regressor's
// derivatives by central differences (route 0), automatic differentiation (route 1) or the adjoint Newton-Euler
// (route 2, the default), without (torque 0) and with (torque 1) a torque limit on every joint (its constraints
// need the torque's derivatives too); the box's share alone, the point and its Jacobian per sample; and one
// evaluation (adjoint route) at a torque-limited design of the PUMA 560, with its torque limits.
// Run: build/benchmarks/bench_excite --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include "excite/excitation_problem.hpp"
#include "puma560_torque_limited_design.hpp"
#include "robot/robot_description.hpp"

namespace {

using namespace jacobid;

// The measured loop: the criterion with its gradient and the constraints with their Jacobian at a new point each time.
void evaluate_repeatedly(benchmark::State& state, excite::ExcitationProblem& problem, Eigen::VectorXd c) {
    Eigen::VectorXd g;
    Eigen::MatrixXd J;
    double step = 1e-9;
    for (auto _ : state) {
        c[0] += step, step = -step;  // a new point every time: nothing cached
        benchmark::DoNotOptimize(problem.criterion(c, &g));
        benchmark::DoNotOptimize(problem.constraint_values(c, &J).data());
    }
    state.counters["samples"] = problem.samples();
}

void evaluation(benchmark::State& state, const char* robot_file) {
    const robot::RobotDescription robot = robot::load_robot_description(std::string(JACOBID_EXAMPLES_DIR "/robots/") + robot_file);
    const auto model = robot::make_robot_model(robot);
    const Eigen::VectorXd x = robot::true_parameters(robot, *model);
    const int n = model->joint_count();
    std::vector<excite::JointLimits> limits(static_cast<std::size_t>(n));
    for (int j = 0; j < n; ++j) limits[static_cast<std::size_t>(j)].lower = robot.joints[static_cast<std::size_t>(j)].lower_limit,
                                limits[static_cast<std::size_t>(j)].upper = robot.joints[static_cast<std::size_t>(j)].upper_limit;
    const Eigen::VectorXd pose = Eigen::VectorXd::Zero(n);
    excite::ProblemSettings settings;
    settings.samples = 400;
    excite::ExcitationProblem problem(*model, x, excite::FourierBasis(10.0, 5, 0.1), pose, limits, settings);
    const excite::DerivativeRoute routes[] = {excite::DerivativeRoute::CentralDifferences, excite::DerivativeRoute::Automatic, excite::DerivativeRoute::Adjoint};
    problem.use_derivative_route(routes[state.range(1)]);
    if (state.range(2) == 1) {
        for (auto& l : limits) l.torque = 1e6;  // never reached: its value changes nothing, its derivatives are computed
        problem.set_limits(limits);
    }
    if (state.range(0) == 1) {
        const std::vector<double> box = {-2, 2, -2, 2, -2, 2};
        problem.set_workspace(excite::make_workspace(robot, "tool", {0.0, 0.0, 0.1}, box, pose));
    }
    evaluate_repeatedly(state, problem, 0.05 * Eigen::VectorXd::Random(problem.variables()));
}

void BM_ExciteEvaluationPuma560(benchmark::State& state) { evaluation(state, "puma560.yaml"); }
void BM_ExciteEvaluationUr5Like(benchmark::State& state) { evaluation(state, "ur5_like.yaml"); }
// The box's own share: the point and its Jacobian at one sample (prepare() does this per sample).
void BM_WorkspacePointAndJacobianPuma560(benchmark::State& state) {
    const robot::RobotDescription robot = robot::load_robot_description(JACOBID_EXAMPLES_DIR "/robots/puma560.yaml");
    const excite::FrameKinematics frame(robot.chain, 5, {}, Eigen::Vector3d(0, 0, 0.1));
    Eigen::VectorXd q = Eigen::VectorXd::Constant(6, 0.3);
    Eigen::Matrix3Xd J;
    for (auto _ : state) {
        q[0] += 1e-9;
        benchmark::DoNotOptimize(frame.point(q, &J).data());
        benchmark::DoNotOptimize(J.data());
    }
}

// One evaluation (adjoint route) at a torque-limited design of the PUMA 560 with its torque limits
// (tests/support/puma560_torque_limited_design.hpp; docs/excite.md, "Speed", "The torque sweep only where the KS
// weight counts"). The torque:1 cases above evaluate at a random small motion under a 1e6 N.m limit, where every
// sample's KS weight is alike; an optimizer's iterates push the torques to their limits at a few peaks. A real
// design's point, not a random one scaled until one torque reaches its limit: the other joints' torques would sit
// far below theirs, where every sample weighs alike again. Stored, not optimized here: a design takes ~20 s, and
// ~50x that under callgrind (callgrind_excite.sh).
void BM_ExciteEvaluationPuma560TorqueLimitedDesign(benchmark::State& state) {
    const robot::RobotDescription robot = robot::load_robot_description(JACOBID_EXAMPLES_DIR "/robots/puma560.yaml");
    const auto model = robot::make_robot_model(robot);
    excite::ExcitationProblem problem = test::puma560_torque_limited_problem(robot, *model, robot::true_parameters(robot, *model), {});
    evaluate_repeatedly(state, problem, test::puma560_torque_limited_design());
    state.counters["torque_swept"] = static_cast<double>(problem.torque_swept().count());
}

BENCHMARK(BM_WorkspacePointAndJacobianPuma560);
BENCHMARK(BM_ExciteEvaluationPuma560)->ArgNames({"box", "route", "torque"})->ArgsProduct({{0, 1}, {0, 1, 2}, {0, 1}})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ExciteEvaluationUr5Like)->ArgNames({"box", "route", "torque"})->ArgsProduct({{0, 1}, {0, 1, 2}, {0, 1}})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ExciteEvaluationPuma560TorqueLimitedDesign)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
