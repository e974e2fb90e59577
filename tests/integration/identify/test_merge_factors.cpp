// SPDX-License-Identifier: MIT
// merge_factors: two systems accumulated apart and merged give the factor of all their rows stacked, and
// the least squares of the merged factors is the dense least squares (SVD) of the stacked rows.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "core/errors.hpp"
#include "identify/solve/least_squares.hpp"
#include "identify/pipeline/merge_factors.hpp"
#include "identify/pipeline/running_qr.hpp"

namespace jacobid::identify {
namespace {

constexpr int kParameters = 5, kJoints = 2;

// Rows [W_j y_j] of a random system: y = W x_true + noise, so the solution is well defined but not exact.
std::vector<Eigen::MatrixXd> random_rows(int rows, unsigned seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> n(0.0, 1.0);
    const Eigen::VectorXd x_true = (Eigen::VectorXd(kParameters) << 3.5, -0.25, 0.43, 0.06, 1.2).finished();
    std::vector<Eigen::MatrixXd> a;
    for (int j = 0; j < kJoints; ++j) {
        Eigen::MatrixXd m(rows, kParameters + 1);
        for (int r = 0; r < rows; ++r) {
            for (int p = 0; p < kParameters; ++p) m(r, p) = n(rng) * (1.0 + p);  // columns of different scales
            m(r, kParameters) = m.row(r).head(kParameters).dot(x_true) + 0.1 * n(rng);
        }
        a.push_back(m);
    }
    return a;
}

JointFactors factors_of(const std::vector<Eigen::MatrixXd>& rows) {
    JointFactors f;
    for (const auto& m : rows) {
        RunningQr qr(kParameters + 1, 64);  // several blocks
        for (Eigen::Index r = 0; r < m.rows(); ++r) {
            const Eigen::VectorXd row = m.row(r).transpose();
            qr.add_row(row.data());
        }
        f.r.push_back(qr.r());
        f.rows.push_back(qr.rows());
    }
    return f;
}

std::vector<std::string> names() { return {"a", "b", "c", "d", "e"}; }

TEST(MergeFactors, IsTheFactorOfTheStackedRowsAndSolvesLikeADenseLeastSquares) {
    const auto first = random_rows(300, 1), second = random_rows(170, 2), third = random_rows(41, 3);
    JointFactors total;
    merge_factors(total, factors_of(first));  // empty total: a copy
    merge_factors(total, factors_of(second));
    merge_factors(total, factors_of(third));
    Eigen::MatrixXd stacked(0, kParameters + 1);
    for (int j = 0; j < kJoints; ++j) {
        const auto js = static_cast<std::size_t>(j);
        Eigen::MatrixXd a(first[js].rows() + second[js].rows() + third[js].rows(), kParameters + 1);
        a << first[js], second[js], third[js];
        EXPECT_EQ(total.rows[js], 511u);
        const Eigen::MatrixXd gram = a.transpose() * a;
        EXPECT_LT((total.r[js].transpose() * total.r[js] - gram).norm(), 1e-12 * gram.norm()) << "joint " << j;
        Eigen::MatrixXd grown(stacked.rows() + a.rows(), a.cols());
        grown << stacked, a;
        stacked = grown;
    }
    // Independent solve: SVD of all joints' rows stacked (no QR, no factors).
    const Eigen::MatrixXd w = stacked.leftCols(kParameters);
    const Eigen::VectorXd y = stacked.col(kParameters);
    const Eigen::VectorXd x = w.jacobiSvd(Eigen::ComputeThinU | Eigen::ComputeThinV).solve(y);
    const LsSolution s = solve_least_squares(total, names());
    ASSERT_EQ(s.identified_count, kParameters);
    EXPECT_LT((s.x - x).norm(), 1e-9 * x.norm()) << s.x.transpose() << "\nvs\n" << x.transpose();
    EXPECT_EQ(s.equations, 2u * 511u);
    EXPECT_NEAR(s.residual_norm, (y - w * x).norm(), 1e-9 * s.residual_norm);
    // Merging is not the first system alone (the test would pass if merge_factors dropped `part`).
    const LsSolution alone = solve_least_squares(factors_of(first), names());
    EXPECT_GT((alone.x - x).norm(), 1e-6 * x.norm());
}

TEST(MergeFactors, MismatchedSystemsAreAnError) {
    JointFactors total = factors_of(random_rows(20, 1));
    JointFactors one_joint = total;
    one_joint.r.pop_back();
    one_joint.rows.pop_back();
    EXPECT_THROW(merge_factors(total, one_joint), InputError);
    JointFactors narrow = total;
    for (auto& r : narrow.r) r = r.topLeftCorner(3, 3).eval();
    EXPECT_THROW(merge_factors(total, narrow), InputError);
}

}  // namespace
}  // namespace jacobid::identify
