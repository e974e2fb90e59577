// SPDX-License-Identifier: MIT
// jacobid excite and simulate --trajectory (issue 17), against independent checks: the Fourier basis's
// rest conditions and its derivatives by finite differences; the criterion's gradient against central
// differences of the criterion itself; every limit at every row of the CSV from finite differences of its
// positions (not from the CSV's own velocity columns); the column-scaled condition number recomputed from the
// CSV with the model's regressor and compared with random point-to-point moves of the same duration; and a
// simulated log that follows the trajectory's reference.
#include <gtest/gtest.h>

#include <Eigen/SVD>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "excite/excitation_problem.hpp"
#include "excite/fourier_trajectory.hpp"
#include "io/csv_table.hpp"
#include "robot/robot_description.hpp"
#include "run_command.hpp"
#include "excite_test_support.hpp"
#include "puma560_torque_limited_design.hpp"
#include "scratch_directory.hpp"

namespace {

namespace fs = std::filesystem;
using jacobid::test::run_command;
using namespace jacobid;

using test::kJacobid;
using test::kTwoLink;

std::string scratch(const std::string& name) { return test::excite_scratch("excite", name); }

TEST(FourierBasis, EveryFunctionIsAtRestAtBothEndsAndItsDerivativesMatchFiniteDifferences) {
    const excite::FourierBasis basis(10.0, 4, 0.13);  // a period that is not a multiple of 1 / f: the correction does all
    Eigen::VectorXd p(8), dp(8), ddp(8);
    for (const double t : {0.0, 10.0 - 1e-12}) {
        basis.evaluate(t, p, dp, ddp);
        EXPECT_LT(p.cwiseAbs().maxCoeff(), 1e-9) << t;
        EXPECT_LT(dp.cwiseAbs().maxCoeff(), 1e-9) << t;
        EXPECT_LT(ddp.cwiseAbs().maxCoeff(), 1e-9) << t;
    }
    const double h = 1e-5;
    Eigen::VectorXd pp(8), pm(8), dpp(8), dpm(8), unused(8);
    for (const double t : {0.7, 3.3, 9.1}) {
        basis.evaluate(t, p, dp, ddp);
        basis.evaluate(t + h, pp, dpp, unused);
        basis.evaluate(t - h, pm, dpm, unused);
        EXPECT_LT(((pp - pm) / (2 * h) - dp).cwiseAbs().maxCoeff(), 1e-7) << t;
        EXPECT_LT(((dpp - dpm) / (2 * h) - ddp).cwiseAbs().maxCoeff(), 1e-6) << t;
    }
}

TEST(ExcitationProblem, CriterionGradientsMatchCentralDifferencesOfTheCriterion) {
  for (const std::string file : {"ur5_like.yaml", "puma560.yaml"}) {
    const robot::RobotDescription robot = robot::load_robot_description(std::string(JACOBID_SOURCE_DIR) + "/examples/robots/" + file);
    const auto model = robot::make_robot_model(robot);
    const Eigen::VectorXd x = robot::true_parameters(robot, *model);
    std::vector<excite::JointLimits> limits(6);
    for (auto& l : limits) l.lower = -2.5, l.upper = 2.5, l.velocity = 3.0, l.torque = 200.0;
    // Every criterion (issue 35: the information criteria weigh per-joint noise and prior scales), with the
    // regressor's derivatives by each route: the adjoint (the default), central differences, automatic differentiation.
    for (const auto criterion : {excite::Criterion::Cond, excite::Criterion::LogDet, excite::Criterion::DOptimal, excite::Criterion::ARelative,
                                 excite::Criterion::ERelative})
    for (const auto route : {excite::DerivativeRoute::Adjoint, excite::DerivativeRoute::CentralDifferences, excite::DerivativeRoute::Automatic}) {
        excite::ProblemSettings settings;
        settings.criterion = criterion;
        settings.samples = 40;
        settings.information = {Eigen::VectorXd::LinSpaced(6, 0.2, 0.02), Eigen::VectorXd::LinSpaced(model->parameter_count(), 0.01, 2.0), 50.0, {}, {}, {}};
        excite::ExcitationProblem problem(*model, x, excite::FourierBasis(5.0, 2, 0.2), Eigen::VectorXd::Zero(6), limits, settings);
        problem.use_derivative_route(route);
        ASSERT_EQ(problem.derivative_route(), route);
        Eigen::VectorXd c = 0.3 * Eigen::VectorXd::Random(problem.variables());
        Eigen::VectorXd g;
        problem.criterion(c, &g);
        Eigen::MatrixXd J;
        const Eigen::VectorXd g0 = problem.constraint_values(c, &J);
        double worst = 0.0, worst_constraint = 0.0;
        auto f = [&](int k, double h) {
            Eigen::VectorXd shifted = c;
            shifted[k] += h;
            return problem.criterion(shifted, nullptr);
        };
        for (int k = 0; k < problem.variables(); k += 3) {
            const double h = 1e-5;
            // Fourth-order central difference: the reference's own error ~h^4, far below the tolerance.
            const double fd = (8.0 * (f(k, h) - f(k, -h)) - (f(k, 2 * h) - f(k, -2 * h))) / (12.0 * h);
            worst = std::max(worst, std::abs(fd - g[k]) / std::max(1.0, std::abs(fd)));
            Eigen::VectorXd cp = c, cm = c;
            cp[k] += 1e-6, cm[k] -= 1e-6;
            const Eigen::VectorXd gfd = (problem.constraint_values(cp, nullptr) - problem.constraint_values(cm, nullptr)) / 2e-6;
            worst_constraint = std::max(worst_constraint, (gfd - J.col(k)).cwiseAbs().maxCoeff());
        }
        // 3e-4: the relative criteria on the PUMA weigh parameters whose predicted variances span ten decades, and
        // the two derivative routes agree to ~1e-8 relative per entry (RegressorDerivatives test), which e-relative's
        // weights amplify to ~1e-4 here; a wrong gradient misses by O(1).
        EXPECT_LT(worst, 3e-4) << file << " " << excite::to_string(criterion) << " " << excite::to_string(route);
        EXPECT_LT(worst_constraint, 1e-4) << file << " " << excite::to_string(criterion) << " " << excite::to_string(route);
    }
  }
}

// The model's torque at each of the problem's samples of c (joints x samples): the regressor at the trajectory's
// own positions, velocities and accelerations, not the problem's.
Eigen::MatrixXd sample_torques(const excite::ExcitationProblem& problem, const robot::RobotModel& model, const Eigen::VectorXd& x, const Eigen::VectorXd& c) {
    const excite::FourierTrajectory trajectory = problem.trajectory(c);
    const int n = model.joint_count();
    Eigen::MatrixXd tau(n, problem.samples()), Y(n, model.parameter_count());
    Eigen::VectorXd q(n), qd(n), qdd(n);
    for (int i = 0; i < problem.samples(); ++i) {
        trajectory.evaluate(problem.basis().period() * i / problem.samples(), q, qd, qdd);
        model.regressor(q.data(), qd.data(), qdd.data(), Y);
        tau.col(i) = Y * x;
    }
    return tau;
}

// The largest difference between two Jacobians' rows, relative to each row's largest entry in `reference`.
double worst_row_difference(const Eigen::MatrixXd& J, const Eigen::MatrixXd& reference) {
    double worst = 0.0;
    for (Eigen::Index r = 0; r < J.rows(); ++r) {
        const double scale = reference.row(r).cwiseAbs().maxCoeff();
        if (scale > 0.0) worst = std::max(worst, (J.row(r) - reference.row(r)).cwiseAbs().maxCoeff() / scale);
    }
    return worst;
}

// The torque constraints' Jacobian takes the torque's derivatives only at the samples whose KS weight is not
// negligible (ProblemSettings::negligible_torque_weight). At a torque-limited design of the PUMA 560 with the
// robot's torque limits (puma560_torque_limited_design.hpp: torques at their limits at a few peaks, as at the
// optimizer's iterates): most samples are left out (193 of 400), every joint's peak is kept, the criterion, its
// gradient and the constraints are unchanged, and the Jacobian equals the one with every sample swept to rounding,
// also after new limits at the same point (the samples kept depend on them: the cached derivatives must not
// outlive them). A coarser floor, which leaves out samples whose weight is 1e-3 of the peak's, misses by far more
// than the tolerance: the comparison catches a wrong skip.
TEST(ExcitationProblem, TorqueDerivativesOnlyWhereTheKsWeightCountsGiveTheSameJacobian) {
    const robot::RobotDescription robot = robot::load_robot_description(std::string(JACOBID_SOURCE_DIR) + "/examples/robots/puma560.yaml");
    const auto model = robot::make_robot_model(robot);
    const Eigen::VectorXd x = robot::true_parameters(robot, *model);
    auto make = [&](double negligible) {
        excite::ProblemSettings settings;
        settings.negligible_torque_weight = negligible;
        return test::puma560_torque_limited_problem(robot, *model, x, settings);
    };
    excite::ExcitationProblem skipping = make(std::numeric_limits<double>::epsilon()), every = make(0.0), coarse = make(400 * 1e-3);
    const Eigen::VectorXd c = test::puma560_torque_limited_design();
    const Eigen::MatrixXd tau = sample_torques(skipping, *model, x, c);

    Eigen::VectorXd gradient, gradient_every;
    EXPECT_EQ(skipping.criterion(c, &gradient), every.criterion(c, &gradient_every));
    EXPECT_EQ(gradient, gradient_every);
    Eigen::MatrixXd J, J_every, J_coarse;
    EXPECT_EQ(skipping.constraint_values(c, &J), every.constraint_values(c, &J_every));
    coarse.constraint_values(c, &J_coarse);
    const Eigen::Index swept = skipping.torque_swept().count();
    EXPECT_EQ(every.torque_swept().count(), every.samples());
    EXPECT_LT(swept, every.samples() / 2);  // most samples left out
    for (int j = 0; j < 6; ++j) {
        Eigen::Index peak = 0;
        tau.row(j).cwiseAbs().maxCoeff(&peak);
        EXPECT_TRUE(skipping.torque_swept()[peak]) << "joint " << j << "'s peak, sample " << peak;
    }
    EXPECT_LT(worst_row_difference(J, J_every), 1e-12);
    EXPECT_GT(worst_row_difference(J_coarse, J_every), 1e-6);

    // Looser limits at the same point: more samples count, and the derivatives cached for the old ones must not be
    // reused (the reference is a problem that never saw the old limits).
    std::vector<excite::JointLimits> limits = test::puma560_torque_limited_limits(robot);
    for (auto& l : limits) l.torque *= 3.0;
    skipping.set_limits(limits);
    excite::ExcitationProblem fresh = make(0.0);
    fresh.set_limits(limits);
    skipping.constraint_values(c, &J);
    fresh.constraint_values(c, &J_every);
    EXPECT_GT(skipping.torque_swept().count(), swept);
    EXPECT_LT(worst_row_difference(J, J_every), 1e-12);
}

// Column-scaled condition number of the model's regressor stacked over the rows of q, qd, qdd (every `stride`-th).
double scaled_cond(const robot::RobotModel& model, const std::vector<std::vector<double>>& q, const std::vector<std::vector<double>>& qd,
                   const std::vector<std::vector<double>>& qdd, std::size_t stride) {
    const int n = model.joint_count();
    std::vector<std::size_t> rows;
    for (std::size_t i = 0; i < q.front().size(); i += stride) rows.push_back(i);
    Eigen::MatrixXd W(static_cast<Eigen::Index>(rows.size()) * n, model.parameter_count());
    Eigen::MatrixXd Y(n, model.parameter_count());
    Eigen::VectorXd a(n), b(n), c(n);
    for (std::size_t r = 0; r < rows.size(); ++r) {
        for (int j = 0; j < n; ++j) a[j] = q[j][rows[r]], b[j] = qd[j][rows[r]], c[j] = qdd[j][rows[r]];
        model.regressor(a.data(), b.data(), c.data(), Y);
        W.middleRows(static_cast<Eigen::Index>(r) * n, n) = Y;
    }
    const Eigen::VectorXd s = W.colwise().norm().cwiseInverse().transpose();
    const Eigen::VectorXd sigma = Eigen::JacobiSVD<Eigen::MatrixXd>(W * s.asDiagonal()).singularValues();
    return sigma[0] / sigma[sigma.size() - 1];
}

TEST(ExciteCli, LimitsHoldAtEveryRowAndTheConditionNumberBeatsRandomMoves) {
    const double vmax = 2.0, amax = 8.0, tmax = 40.0;
    const std::string traj = scratch("two_link.csv"), json_path = scratch("two_link.json"), png = scratch("two_link.png");
    const auto r = run_command(kJacobid + " excite --criterion cond --robot " + kTwoLink + " --duration 20 --harmonics 4 --base-frequency 0.1 --velocity-limit 2 " +
                               "--acceleration-limit 8 --torque-limit 40 --time-limit 20 --quiet -o " + traj + " --json " + json_path + " --plot " + png);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_GT(fs::file_size(png), 1000u);
    const io::CsvTable t = io::read_csv(traj);
    ASSERT_EQ(t.rows(), 20001u);
    const double dt = 1e-3;
    const robot::RobotDescription robot = robot::load_robot_description(kTwoLink);
    const auto model = robot::make_robot_model(robot);
    const Eigen::VectorXd x = robot::true_parameters(robot, *model);
    std::vector<std::vector<double>> q(2), qd(2), qdd(2);
    for (int j = 0; j < 2; ++j) {
        const auto& p = t.column("q" + std::to_string(j + 1));
        q[static_cast<std::size_t>(j)] = p;
        auto& v = qd[static_cast<std::size_t>(j)];
        auto& a = qdd[static_cast<std::size_t>(j)];
        v.assign(p.size(), 0.0), a.assign(p.size(), 0.0);
        for (std::size_t i = 1; i + 1 < p.size(); ++i) {
            v[i] = (p[i + 1] - p[i - 1]) / (2 * dt);
            a[i] = (p[i + 1] - 2 * p[i] + p[i - 1]) / (dt * dt);
        }
        const auto& jd = robot.joints[static_cast<std::size_t>(j)];
        for (std::size_t i = 0; i < p.size(); ++i) {
            ASSERT_GE(p[i], jd.lower_limit) << "joint " << j + 1 << " row " << i;
            ASSERT_LE(p[i], jd.upper_limit) << "joint " << j + 1 << " row " << i;
            ASSERT_LE(std::abs(v[i]), vmax * (1 + 1e-6)) << "joint " << j + 1 << " row " << i;
            ASSERT_LE(std::abs(a[i]), amax * (1 + 1e-4)) << "joint " << j + 1 << " row " << i;
        }
        // The CSV's velocities are the positions' derivative.
        EXPECT_NEAR(v[5000], t.column("qd" + std::to_string(j + 1))[5000], 1e-5);
        // At rest at both ends of every period (10 s).
        for (const std::size_t i : {std::size_t{0}, std::size_t{10000}, std::size_t{20000}}) EXPECT_NEAR(t.column("qd" + std::to_string(j + 1))[i], 0.0, 1e-9);
    }
    Eigen::MatrixXd Y(2, model->parameter_count());
    for (std::size_t i = 1; i + 1 < q[0].size(); i += 7) {
        const double qa[2] = {q[0][i], q[1][i]}, va[2] = {qd[0][i], qd[1][i]}, aa[2] = {qdd[0][i], qdd[1][i]};
        model->regressor(qa, va, aa, Y);
        const Eigen::Vector2d tau = Y * x;
        ASSERT_LE(tau.cwiseAbs().maxCoeff(), tmax * (1 + 1e-3)) << "row " << i;
    }
    // Random moves of the same duration within the same position limits.
    const std::string moves = scratch("moves.csv"), states = scratch("moves_states.csv");
    ASSERT_EQ(run_command(kJacobid + " simulate --quiet --robot " + kTwoLink + " --duration 20 -o " + moves + " --states " + states).exit_code, 0);
    const io::CsvTable m = io::read_csv(states);
    std::vector<std::vector<double>> mq(2), mqd(2), mqdd(2);
    for (int j = 0; j < 2; ++j) {
        mq[static_cast<std::size_t>(j)] = m.column("q" + std::to_string(j + 1));
        mqd[static_cast<std::size_t>(j)] = m.column("qd" + std::to_string(j + 1));
        mqdd[static_cast<std::size_t>(j)] = m.column("qdd" + std::to_string(j + 1));
    }
    const double excited = scaled_cond(*model, q, qd, qdd, 50), random = scaled_cond(*model, mq, mqd, mqdd, 50);
    const nlohmann::json j = nlohmann::json::parse(std::ifstream(json_path));
    EXPECT_NEAR(j["cond"].get<double>(), excited, 0.05 * excited) << "the JSON's cond is not the trajectory's";
    // Two links are easy to excite (random moves give ~2.7): the optimum must still be better.
    EXPECT_LT(excited, random) << "excite " << excited << ", random moves " << random;
    ASSERT_EQ(j["joints"].size(), 2u);
    EXPECT_EQ(j["joints"][0]["a"].size(), 4u);
    EXPECT_LE(j["joints"][1]["limit_use"]["velocity"].get<double>(), 1.0);
}

TEST(SimulateTrajectory, TheLogFollowsTheGivenReferencePeriodAfterPeriod) {
    const std::string traj = scratch("follow.csv");
    ASSERT_EQ(run_command(kJacobid + " excite --robot " + kTwoLink + " --duration 10 --harmonics 3 --base-frequency 0.2 --velocity-limit 2 --time-limit 5 " +
                          "--starts 1 --quiet -o " + traj)
                  .exit_code,
              0);
    const std::string log = scratch("follow_log.csv");
    const auto r = run_command(kJacobid + " simulate --quiet --robot " + kTwoLink + " --trajectory " + traj + " -o " + log);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const io::CsvTable ref = io::read_csv(traj), out = io::read_csv(log);
    ASSERT_EQ(out.rows(), ref.rows()) << "--duration defaults to the trajectory's length";
    // The controller's reference at the control instants is the table's row (1 kHz both).
    for (std::size_t i = 0; i < out.rows(); i += 997) {
        EXPECT_NEAR(out.column("q_ref1")[i], ref.column("q1")[i], 1e-9) << i;
        EXPECT_NEAR(out.column("qd_ref2")[i], ref.column("qd2")[i], 1e-9) << i;
    }
    // The tracked position stays close to the reference (PD at 30 rad/s).
    double worst = 0.0;
    for (std::size_t i = 0; i < out.rows(); ++i) worst = std::max(worst, std::abs(out.column("q1")[i] - ref.column("q1")[i]));
    EXPECT_LT(worst, 0.05);
    // Longer than the table: it repeats (second period = first).
    const std::string twice = scratch("follow_twice.csv");
    ASSERT_EQ(run_command(kJacobid + " simulate --quiet --robot " + kTwoLink + " --trajectory " + traj + " --duration 20 -o " + twice).exit_code, 0);
    const io::CsvTable two = io::read_csv(twice);
    ASSERT_EQ(two.rows(), 20001u);
    EXPECT_NEAR(two.column("q_ref1")[13000], ref.column("q1")[3000], 1e-9);
}

TEST(ExciteCli, BadInputIsOneLineNamingTheOption) {
    struct Case {
        std::string args, expected;
    };
    const std::vector<Case> cases = {
        {"--duration 15 --base-frequency 0.1", "--duration 15"},
        {"--pose 3,0", "--pose: joint 1"},
        {"--velocity-limit 1,2,3", "--velocity-limit: 3 values"},
        {"--torque-limit -1", "--torque-limit: joint 1"},
        {"--harmonics 0", "--harmonics 0"},
    };
    for (const auto& c : cases) {
        const auto r = run_command(kJacobid + " excite --quiet --robot " + kTwoLink + " -o " + scratch("bad.csv") + " " + c.args);
        EXPECT_EQ(r.exit_code, 2) << c.args;
        EXPECT_NE(r.err.find(c.expected), std::string::npos) << c.args << ": " << r.err;
    }
    std::ofstream(scratch("jump.csv")) << "t,q1,q2,qd1,qd2,qdd1,qdd2\n0,0,0,0,0,0,0\n0.001,0.1,0,0,0,0,0\n";
    const auto jump = run_command(kJacobid + " simulate --quiet --robot " + kTwoLink + " --trajectory " + scratch("jump.csv") + " -o " + scratch("x.csv"));
    EXPECT_EQ(jump.exit_code, 2);
    EXPECT_NE(jump.err.find("line 3, column q1: the trajectory must end where it starts"), std::string::npos) << jump.err;
    std::ofstream(scratch("uneven.csv")) << "t,q1,q2,qd1,qd2,qdd1,qdd2\n0,0,0,0,0,0,0\n0.001,0,0,0,0,0,0\n0.003,0,0,0,0,0,0\n";
    const auto uneven = run_command(kJacobid + " simulate --quiet --robot " + kTwoLink + " --trajectory " + scratch("uneven.csv") + " -o " + scratch("x.csv"));
    EXPECT_EQ(uneven.exit_code, 2);
    EXPECT_NE(uneven.err.find("line 4, column t"), std::string::npos) << uneven.err;
}

}  // namespace
