// SPDX-License-Identifier: MIT
#include "identify/solve/normal_equations.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

namespace jacobid::identify {
namespace {

// 1 / sqrt(G_ii): the column scaling that gives G a unit diagonal (0 for a zero column).
Eigen::VectorXd unit_diagonal_scale(const Eigen::MatrixXd& G) {
    Eigen::VectorXd scale(G.rows());
    for (Eigen::Index i = 0; i < G.rows(); ++i) scale[i] = G(i, i) > 0.0 ? 1.0 / std::sqrt(G(i, i)) : 0.0;
    return scale;
}

}  // namespace

SubsetFit solve_subset(const GramSums& s) {
    SubsetFit f;
    const Eigen::Index k = s.G.rows();
    const Eigen::VectorXd scale = unit_diagonal_scale(s.G);
    if ((scale.array() == 0.0).any()) return f;
    const Eigen::MatrixXd A = scale.asDiagonal() * s.G * scale.asDiagonal();
    const Eigen::LDLT<Eigen::MatrixXd> ldlt(A);
    if (ldlt.info() != Eigen::Success || !(ldlt.vectorD().minCoeff() > 1e-10)) return f;
    const Eigen::VectorXd z = ldlt.solve(scale.asDiagonal() * s.b);
    f.x = scale.asDiagonal() * z;
    f.inverse = scale.asDiagonal() * ldlt.solve(Eigen::MatrixXd::Identity(k, k)) * scale.asDiagonal();
    f.rss = std::max(0.0, s.yy - f.x.dot(s.b));
    f.ok = true;
    return f;
}

Eigen::VectorXd solve_minimum_norm(const GramSums& s) {
    const SubsetFit fit = solve_subset(s);
    if (fit.ok) return fit.x;
    const Eigen::Index k = s.G.rows();
    const Eigen::VectorXd scale = unit_diagonal_scale(s.G);
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(scale.asDiagonal() * s.G * scale.asDiagonal());
    const Eigen::VectorXd& lambda = eig.eigenvalues();
    const double cut = 1e-10 * std::max(lambda.maxCoeff(), 0.0);
    Eigen::VectorXd inv = Eigen::VectorXd::Zero(k);
    for (Eigen::Index i = 0; i < k; ++i) inv[i] = lambda[i] > cut ? 1.0 / lambda[i] : 0.0;
    const Eigen::MatrixXd& V = eig.eigenvectors();
    return scale.asDiagonal() * (V * (inv.asDiagonal() * (V.transpose() * (scale.asDiagonal() * s.b))));
}

double prediction_sse(const GramSums& h, const Eigen::VectorXd& x) { return std::max(0.0, h.yy - 2.0 * x.dot(h.b) + x.dot(h.G * x)); }

}  // namespace jacobid::identify
