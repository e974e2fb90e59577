// SPDX-License-Identifier: MIT
#include "identify/normal_equations.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>

namespace jacobid::identify {

SubsetFit solve_subset(const GramSums& s) {
    SubsetFit f;
    const Eigen::Index k = s.G.rows();
    Eigen::VectorXd scale(k);
    for (Eigen::Index i = 0; i < k; ++i) scale[i] = s.G(i, i) > 0.0 ? 1.0 / std::sqrt(s.G(i, i)) : 0.0;
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

double prediction_sse(const GramSums& h, const Eigen::VectorXd& x) { return std::max(0.0, h.yy - 2.0 * x.dot(h.b) + x.dot(h.G * x)); }

}  // namespace jacobid::identify
