// SPDX-License-Identifier: MIT
#include "identify/drive_gains/drive_gains_tls.hpp"

#include <Eigen/Dense>
#include <cmath>

namespace jacobid::identify {

DriveGainEstimate drive_gains_tls(const DriveGainResult& result) {
    const LsSolution& ls = result.method.solution;
    const int c = result.parameter_count, p = result.payload_columns, n = result.joints;
    std::vector<double> weights = ls.joint_weights;
    if (weights.size() != result.factors.r.size()) weights.assign(result.factors.r.size(), 1.0);
    const Eigen::MatrixXd factor = stacked_factor(result.factors, weights);

    // Columns: the identified exact ones, then the gains (scaled to N.m), then the known payload's.
    std::vector<int> exact;
    for (int k = 0; k < c + p; ++k) {
        if (ls.identified[static_cast<std::size_t>(k)]) exact.push_back(k);
    }
    const int e = static_cast<int>(exact.size());
    Eigen::MatrixXd columns(factor.rows(), e + n + 1);
    for (int k = 0; k < e; ++k) columns.col(k) = factor.col(exact[static_cast<std::size_t>(k)]);
    const Eigen::VectorXd scale = result.least_squares.gains;
    for (int j = 0; j < n; ++j) columns.col(e + j) = factor.col(c + p + j) * scale[j];
    columns.col(e + n) = factor.col(c + p + n);
    const Eigen::MatrixXd r = Eigen::HouseholderQR<Eigen::MatrixXd>(columns).matrixQR().triangularView<Eigen::Upper>();

    // R22 [g / g_ls; -1] = 0 in the TLS sense.
    const Eigen::MatrixXd r22 = r.block(e, e, n + 1, n + 1);
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(r22, Eigen::ComputeFullV);
    const Eigen::VectorXd v = svd.matrixV().col(n);
    DriveGainEstimate out;
    out.estimator = "tls";
    out.std_dev = Eigen::VectorXd::Constant(n, std::nan(""));
    const Eigen::VectorXd relative = v.head(n) / -v[n];
    out.gains = scale.cwiseProduct(relative);
    // R11 x1 + R12 g' - r1 = 0 (g' the scaled gains).
    const Eigen::VectorXd rhs = r.block(0, e + n, e, 1) - r.block(0, e, e, n) * relative;
    const Eigen::VectorXd x1 = r.topLeftCorner(e, e).triangularView<Eigen::Upper>().solve(rhs);
    out.payload = result.payload.known;
    for (int k = 0; k < p; ++k) out.payload[result.payload.unknown[static_cast<std::size_t>(k)]] = std::nan("");
    for (int k = 0; k < e; ++k) {
        const int column = exact[static_cast<std::size_t>(k)];
        if (column >= c) out.payload[result.payload.unknown[static_cast<std::size_t>(column - c)]] = x1[k];
    }
    return out;
}

}  // namespace jacobid::identify
