// SPDX-License-Identifier: MIT
#include "robot/base_parameters.hpp"

#include <fmt/core.h>

#include <Eigen/QR>
#include <cmath>
#include <random>
#include <stdexcept>

namespace jacobid::robot {
namespace {

constexpr double kPi = 3.14159265358979323846;

// W stacked over random states, each column scaled to unit norm (so the tolerances are relative).
Eigen::MatrixXd random_regressor(int n, int p, const std::vector<bool>& prismatic, const StandardRegressorFunction& regressor, int states,
                                 unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    Eigen::MatrixXd W(static_cast<Eigen::Index>(states) * n, p);
    Eigen::MatrixXd D(n, p);
    std::vector<double> q(static_cast<std::size_t>(n)), qd(q), qdd(q);
    for (int s = 0; s < states; ++s) {
        for (std::size_t j = 0; j < q.size(); ++j) {
            q[j] = unit(rng) * (prismatic[j] ? 1.0 : kPi);
            qd[j] = 2.0 * unit(rng);
            qdd[j] = 5.0 * unit(rng);
        }
        regressor(q.data(), qd.data(), qdd.data(), D);
        W.middleRows(static_cast<Eigen::Index>(s) * n, n) = D;
    }
    return W;
}

}  // namespace

BaseParameterSet compute_base_parameters(int n, const std::vector<std::string>& names, const std::vector<int>& priority,
                                         const std::vector<bool>& prismatic, const StandardRegressorFunction& regressor,
                                         const BaseParameterSettings& settings) {
    const int p = static_cast<int>(names.size());
    const int states = settings.states > 0 ? settings.states : std::max(20, (3 * p + n - 1) / n);
    Eigen::MatrixXd W = random_regressor(n, p, prismatic, regressor, states, settings.seed);

    // A description with absurd numbers (a length of 1e84 m, say) gives an infinite or NaN regressor; the
    // rank decisions below would then be meaningless, so refuse it here with a message the user can act on.
    if (!W.allFinite()) {
        throw std::invalid_argument("the regressor is not finite for random joint states: check the lengths, offsets and axes of the description");
    }
    BaseParameterSet base;
    const Eigen::VectorXd norms = W.colwise().norm();
    const double largest = norms.maxCoeff();
    std::vector<int> nonzero;
    for (int c : priority) {
        if (norms[c] <= 1e-12 * largest) {
            base.no_effect.push_back(c);
        } else {
            W.col(c) /= norms[c];
            nonzero.push_back(c);
        }
    }

    if (nonzero.empty()) throw std::invalid_argument("no parameter has any effect on the joint torques: the description has no moving joint");
    // Rank of the nonzero columns by QR with column pivoting.
    Eigen::MatrixXd Wn(W.rows(), static_cast<Eigen::Index>(nonzero.size()));
    for (std::size_t k = 0; k < nonzero.size(); ++k) Wn.col(static_cast<Eigen::Index>(k)) = W.col(nonzero[k]);
    Eigen::ColPivHouseholderQR<Eigen::MatrixXd> pivoted(Wn);
    pivoted.setThreshold(settings.tolerance);
    base.pivoted_qr_rank = static_cast<int>(pivoted.rank());

    // Greedy choice in priority order: Gram-Schmidt (twice, for orthogonality to rounding) against the kept columns.
    Eigen::MatrixXd Q(W.rows(), base.pivoted_qr_rank + 1);
    int kept = 0;
    std::vector<int> dropped;
    for (int c : nonzero) {
        Eigen::VectorXd v = W.col(c);
        for (int pass = 0; pass < 2; ++pass) {
            if (kept > 0) v -= Q.leftCols(kept) * (Q.leftCols(kept).transpose() * v);
        }
        const double residual = v.norm();  // the column has unit norm
        if (residual > settings.tolerance && kept <= base.pivoted_qr_rank) {
            Q.col(kept++) = v / residual;
            base.base_columns.push_back(c);
        } else {
            dropped.push_back(c);
        }
    }
    if (kept != base.pivoted_qr_rank) {
        throw std::runtime_error(fmt::format("base parameters: pivoted QR rank {} but {} independent columns in priority order "
                                             "(ill-conditioned random states; try another seed)",
                                             base.pivoted_qr_rank, kept));
    }

    // Regrouping coefficients in unscaled units: w_d / |w_d| = W_B diag(1/|w_b|) beta' => beta_bd = beta'_bd |w_d| / |w_b|.
    Eigen::MatrixXd WB(W.rows(), kept);
    for (int b = 0; b < kept; ++b) WB.col(b) = W.col(base.base_columns[static_cast<std::size_t>(b)]);
    const Eigen::HouseholderQR<Eigen::MatrixXd> qr(WB);
    base.regrouping = Eigen::MatrixXd::Zero(kept, p);
    std::vector<bool> regrouped(static_cast<std::size_t>(kept), false);
    for (int b = 0; b < kept; ++b) base.regrouping(b, base.base_columns[static_cast<std::size_t>(b)]) = 1.0;
    for (int d : dropped) {
        const Eigen::VectorXd beta = qr.solve(W.col(d));
        for (int b = 0; b < kept; ++b) {
            const double coefficient = beta[b] * norms[d] / norms[base.base_columns[static_cast<std::size_t>(b)]];
            if (std::abs(coefficient) < settings.coefficient_zero) continue;
            base.regrouping(b, d) = coefficient;
            regrouped[static_cast<std::size_t>(b)] = true;
        }
    }
    for (int b = 0; b < kept; ++b) {
        const std::string& name = names[static_cast<std::size_t>(base.base_columns[static_cast<std::size_t>(b)])];
        base.base_names.push_back(regrouped[static_cast<std::size_t>(b)] ? name + "R" : name);
    }
    return base;
}

std::vector<std::string> regrouping_relations(const BaseParameterSet& base, const std::vector<std::string>& names) {
    std::vector<std::string> lines;
    for (Eigen::Index b = 0; b < base.regrouping.rows(); ++b) {
        std::string line = base.base_names[static_cast<std::size_t>(b)] + " =";
        bool first = true;
        for (Eigen::Index c = 0; c < base.regrouping.cols(); ++c) {
            const double k = base.regrouping(b, c);
            if (k == 0.0) continue;
            const std::string& name = names[static_cast<std::size_t>(c)];
            const char* sign = k < 0.0 ? "-" : "+";
            const double magnitude = std::abs(k);
            const std::string term = std::abs(magnitude - 1.0) < 1e-12 ? name : fmt::format("{:.6g}*{}", magnitude, name);
            line += first ? (k < 0.0 ? " -" + term : " " + term) : fmt::format(" {} {}", sign, term);
            first = false;
        }
        lines.push_back(line);
    }
    return lines;
}

}  // namespace jacobid::robot
