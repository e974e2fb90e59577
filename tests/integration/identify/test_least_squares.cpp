// SPDX-License-Identifier: MIT
// Running QR and the LS statistics against direct, independent computations (Eigen's column-pivoted QR
// on the full matrix, normal equations for the covariance on a well-conditioned problem).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <random>

#include "identify/solve/least_squares.hpp"
#include "identify/pipeline/running_qr.hpp"

namespace {

using jacobid::identify::JointFactors;
using jacobid::identify::RunningQr;

struct Problem {
    Eigen::MatrixXd w;
    Eigen::VectorXd y;
};

Problem random_problem(int rows, int cols, double noise, unsigned seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> n(0, 1);
    Problem p{Eigen::MatrixXd(rows, cols), Eigen::VectorXd(rows)};
    for (int i = 0; i < rows; ++i)
        for (int j = 0; j < cols; ++j) p.w(i, j) = n(rng) * (1.0 + j);
    Eigen::VectorXd x(cols);
    for (int j = 0; j < cols; ++j) x(j) = 0.5 + j;
    p.y = p.w * x;
    for (int i = 0; i < rows; ++i) p.y(i) += noise * n(rng);
    return p;
}

Eigen::MatrixXd factor(const Problem& p, int block_rows) {
    RunningQr qr(static_cast<int>(p.w.cols()) + 1, block_rows);
    Eigen::VectorXd row(p.w.cols() + 1);
    for (Eigen::Index i = 0; i < p.w.rows(); ++i) {
        row << p.w.row(i).transpose(), p.y(i);
        qr.add_row(row.data());
    }
    return qr.r();
}

TEST(RunningQr, FactorReproducesTheGramMatrixForAnyBlockSize) {
    const Problem p = random_problem(1000, 5, 0.1, 1);
    Eigen::MatrixXd a(p.w.rows(), p.w.cols() + 1);
    a << p.w, p.y;
    const Eigen::MatrixXd gram = a.transpose() * a;
    for (int block : {1, 7, 64, 1000, 4096}) {
        const Eigen::MatrixXd r = factor(p, block);
        EXPECT_LT((r.transpose() * r - gram).norm(), 1e-10 * gram.norm()) << block;
        EXPECT_TRUE(r.isUpperTriangular(0.0)) << block;
    }
}

TEST(LeastSquares, SolutionAndStatisticsMatchDirectComputation) {
    const int rows = 2000, cols = 4;
    const Problem p = random_problem(rows, cols, 0.05, 2);
    JointFactors f;
    f.r.push_back(factor(p, 128));
    f.rows.push_back(rows);
    const auto s = jacobid::identify::solve_least_squares(f, {"a", "b", "c", "d"});
    const Eigen::VectorXd x = p.w.colPivHouseholderQr().solve(p.y);
    const double residual = (p.y - p.w * x).norm();
    const double sigma = residual / std::sqrt(rows - cols);
    const Eigen::MatrixXd cov = sigma * sigma * (p.w.transpose() * p.w).inverse();
    for (int j = 0; j < cols; ++j) {
        EXPECT_NEAR(s.x(j), x(j), 1e-10 * std::abs(x(j)));
        EXPECT_NEAR(s.std_dev(j), std::sqrt(cov(j, j)), 1e-8 * std::sqrt(cov(j, j)));
        EXPECT_NEAR(s.rel_std_percent(j), 100 * std::sqrt(cov(j, j)) / std::abs(x(j)), 1e-6);
    }
    EXPECT_NEAR(s.residual_norm, residual, 1e-9 * residual);
    EXPECT_NEAR(s.relative_error_norm, residual / p.y.norm(), 1e-12);
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(p.w);
    const auto sv = svd.singularValues();
    EXPECT_NEAR(s.cond, sv(0) / sv(cols - 1), 1e-8 * s.cond);
    EXPECT_EQ(s.equations, static_cast<std::size_t>(rows));
    EXPECT_EQ(s.rank, cols);
    EXPECT_TRUE(s.unidentifiable.empty());
}

TEST(LeastSquares, ColinearAndZeroColumnsAreReportedNotFitted) {
    Problem p = random_problem(500, 4, 0.01, 3);
    p.w.col(2) = 2.0 * p.w.col(0);  // only 2 a + c is visible
    p.w.col(3).setZero();           // d is invisible
    JointFactors f;
    f.r.push_back(factor(p, 100));
    f.rows.push_back(500);
    const auto s = jacobid::identify::solve_least_squares(f, {"a", "b", "c", "d"});
    EXPECT_EQ(s.rank, 2);
    EXPECT_TRUE(s.identified[1]);
    EXPECT_FALSE(s.identified[3]);
    EXPECT_TRUE(std::isnan(s.x(3)));
    EXPECT_EQ(s.identified[0] + s.identified[2], 1);  // one of the colinear pair is kept, never both
    bool zero_reported = false, pair_reported = false;
    for (const auto& u : s.unidentifiable) {
        if (u.zero_column && u.parameters == std::vector<int>{3}) zero_reported = true;
        if (!u.zero_column && u.parameters.size() == 2) {
            // W a = 0 with a = (1, -0.5) on (a, c) up to sign and scale (max |a| = 1).
            const double ratio = u.coefficients[1] / u.coefficients[0];
            pair_reported = std::abs(ratio + 0.5) < 1e-6 || std::abs(ratio + 2.0) < 1e-6;
        }
    }
    EXPECT_TRUE(zero_reported);
    EXPECT_TRUE(pair_reported);
}

TEST(LeastSquares, WeightedLsUsesEachJointsResidualLevel) {
    // Two joints see the same parameters with noise 0.01 and 0.1: Gautier's weights are 1 / sigma_j.
    const Problem a = random_problem(3000, 3, 0.01, 4), b = random_problem(3000, 3, 0.1, 5);
    JointFactors f;
    f.r = {factor(a, 256), factor(b, 256)};
    f.rows = {3000, 3000};
    jacobid::identify::SolveOptions o;
    o.weighted = true;
    const auto s = jacobid::identify::solve_least_squares(f, {"x1", "x2", "x3"}, o);
    ASSERT_EQ(s.joint_weights.size(), 2u);
    EXPECT_NEAR(s.joint_weights[0], 1.0 / 0.01, 0.1 / 0.01);
    EXPECT_NEAR(s.joint_weights[1], 1.0 / 0.1, 0.1 / 0.1);
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(s.x(j), 0.5 + j, 1e-3);
}

}  // namespace
