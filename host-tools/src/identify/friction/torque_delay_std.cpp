// SPDX-License-Identifier: MIT
#include "identify/friction/torque_delay_std.hpp"

#include <Eigen/Dense>
#include <algorithm>

#include "identify/solve/residual_correlation.hpp"

namespace jacobid::identify {

namespace {

using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// The fitted parameters with 0 for those not identified (not in the model that was solved).
Eigen::VectorXd coefficients(const LsSolution& s) {
    Eigen::VectorXd x = s.x;
    for (Eigen::Index i = 0; i < x.size(); ++i) {
        if (!s.identified[static_cast<std::size_t>(i)]) x[i] = 0.0;
    }
    return x;
}

// Per joint (columns) and row: the residual at the estimate, de/dd, and the score's factor a (de/dd without
// the parameters' noise term under WLS), with the identified columns of W and the joints' weights.
struct ScoreParts {
    Eigen::MatrixXd e, de, a;
    std::vector<Eigen::MatrixXd> w;
    std::vector<double> s2;
};

bool score_parts(const RowCollector& rows, const ShiftedFit (&around)[3], double sample_period, double delay, ScoreParts& out) {
    if (!rows.complete() || rows.rows() == 0) return false;
    const std::vector<std::size_t>& samples = rows.samples();
    for (const ShiftedFit& f : around) {
        const long long lo = static_cast<long long>(samples.front()) + f.shift, hi = static_cast<long long>(samples.back()) + f.shift;
        if (lo < static_cast<long long>(rows.covered_from()) || hi >= static_cast<long long>(rows.covered_to())) return false;
    }
    const auto n = static_cast<Eigen::Index>(rows.rows()), p = static_cast<Eigen::Index>(rows.parameters());
    const auto joints = static_cast<Eigen::Index>(rows.joints());
    const LsSolution& best = *around[1].solution;
    const Eigen::VectorXd x[3] = {coefficients(*around[0].solution), coefficients(best), coefficients(*around[2].solution)};
    const double step = delay - around[1].shift * sample_period;  // from the grid point to the estimate
    std::vector<int> kept;
    for (Eigen::Index i = 0; i < p; ++i) {
        if (best.identified[static_cast<std::size_t>(i)]) kept.push_back(static_cast<int>(i));
    }
    out.e.resize(n, joints);
    out.de.resize(n, joints);
    out.w.assign(static_cast<std::size_t>(joints), {});
    out.s2.assign(static_cast<std::size_t>(joints), 1.0);
    Eigen::MatrixXd gram = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(kept.size()), static_cast<Eigen::Index>(kept.size()));
    Eigen::VectorXd cross = Eigen::VectorXd::Zero(gram.rows());
    for (Eigen::Index j = 0; j < joints; ++j) {
        const auto ju = static_cast<std::size_t>(j);
        const Eigen::Map<const RowMajor> w(rows.w(ju).data(), n, p);
        const std::vector<double>& filtered = rows.filtered_torque()[ju];
        Eigen::VectorXd residual[3];
        for (int i = 0; i < 3; ++i) {
            Eigen::VectorXd y(n);
            for (Eigen::Index m = 0; m < n; ++m) y[m] = filtered[static_cast<std::size_t>(static_cast<long long>(samples[static_cast<std::size_t>(m)]) + around[i].shift)];
            residual[i] = y - w * x[i];
        }
        // e is linear in d between grid points (the torque is interpolated linearly): the central difference
        // is its derivative at the grid point, up to the kink there.
        out.de.col(j) = (residual[2] - residual[0]) / (2.0 * sample_period);
        out.e.col(j) = residual[1] + step * out.de.col(j);
        out.w[ju] = w(Eigen::all, kept);
        out.s2[ju] = best.joint_weights[ju] * best.joint_weights[ju];
        gram.noalias() += out.s2[ju] * out.w[ju].transpose() * out.w[ju];
        cross.noalias() += out.w[ju].transpose() * out.de.col(j);
    }
    // The parameters are fitted to the same noise: with e = eps - W (x^ - x0), x^ - x0 = A^-1 sum_j s_j^2 W_j^T
    // eps_j, S = sum eps (de/dd - s_j^2 W A^-1 c) with c = sum W^T de/dd. Under OLS c = 0 (de/dd is
    // orthogonal to W); under WLS it is not.
    out.a = out.de;
    if (gram.rows() > 0) {
        const Eigen::VectorXd z = gram.ldlt().solve(cross);
        for (Eigen::Index j = 0; j < joints; ++j) out.a.col(j) -= out.s2[static_cast<std::size_t>(j)] * (out.w[static_cast<std::size_t>(j)] * z);
    }
    return true;
}

}  // namespace

double hac_leverage_factor(const Eigen::MatrixXd& a, const Eigen::MatrixXd& de, const std::vector<Eigen::MatrixXd>& w,
                           const std::vector<double>& s2, const std::vector<double>& lambda, int lags, double curvature_half) {
    const Eigen::Index n = a.rows(), k = w.empty() ? 0 : w.front().cols();
    double variance = 0.0;  // V = sum_j lambda_j |a_j|^2: Var(S) for noise white in the long run
    Eigen::MatrixXd v = Eigen::MatrixXd::Zero(n, k), v_noise = v, gram = Eigen::MatrixXd::Zero(k, k), meat = gram;
    Eigen::VectorXd a1 = Eigen::VectorXd::Zero(n);
    for (std::size_t j = 0; j < w.size(); ++j) {
        const auto col = a.col(static_cast<Eigen::Index>(j));
        variance += lambda[j] * col.squaredNorm();
        a1 += lambda[j] * col.cwiseAbs2();
        if (k == 0) continue;
        v += col.asDiagonal() * w[j];
        v_noise += (s2[j] * lambda[j] * col).asDiagonal() * w[j];
        gram += s2[j] * w[j].transpose() * w[j];
        meat += s2[j] * s2[j] * lambda[j] * w[j].transpose() * w[j];
    }
    if (!(variance > 0.0)) return 1.0;
    double shortfall = 0.0;
    if (k > 0) {
        // E[g_t g_u] of e = (I - P) eps: Lambda - P Lambda - Lambda P^T + P Lambda P^T; row t of z is v_t^T A^-1.
        const Eigen::MatrixXd z = gram.ldlt().solve(v.transpose()).transpose();
        shortfall += 2.0 * bartlett_cross_sum(z, v_noise, lags) - bartlett_cross_sum(z * meat, z, lags);
    }
    // e at the estimate is e0 - c de with c = a^T e0 / S': E[c g0_t] = sum_j lambda_j a_jt^2 / S', E[c^2] = V / S'^2.
    const Eigen::VectorXd along = a.cwiseProduct(de).rowwise().sum();
    shortfall += 2.0 * bartlett_cross_sum(a1, along, lags) / curvature_half - variance * bartlett_cross_sum(along, along, lags) / (curvature_half * curvature_half);
    // Restores at most 4 x: past it the rows hold too little beyond what was fitted for any HAC sum.
    const double left = variance - shortfall;
    return left > 0.25 * variance ? std::max(variance / left, 1.0) : 4.0;
}

DelayScoreVariance torque_delay_score_variance(const RowCollector& rows, const ShiftedFit (&around)[3], double sample_period, double delay,
                                               double curvature) {
    DelayScoreVariance r;
    ScoreParts parts;
    if (!(curvature > 0.0) || !score_parts(rows, around, sample_period, delay, parts)) return r;
    r.rows = rows.rows();
    r.lags = newey_west_lags(r.rows);
    const Eigen::VectorXd g = parts.e.cwiseProduct(parts.a).rowwise().sum();
    const double hac = bartlett_long_run_variance(g, r.lags);
    std::vector<double> lambda;  // each joint's long-run residual variance per row
    for (Eigen::Index j = 0; j < parts.e.cols(); ++j) {
        lambda.push_back(bartlett_long_run_variance(parts.e.col(j), r.lags) / static_cast<double>(r.rows));
    }
    r.leverage_factor = hac_leverage_factor(parts.a, parts.de, parts.w, parts.s2, lambda, r.lags, 0.5 * curvature);
    r.variance = hac * r.leverage_factor;
    return r;
}

}  // namespace jacobid::identify
