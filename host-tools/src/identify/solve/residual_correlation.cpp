// SPDX-License-Identifier: MIT
#include "identify/solve/residual_correlation.hpp"

#include <algorithm>
#include <cmath>

namespace jacobid::identify {

LaggedProducts::LaggedProducts(int columns, int lags, int block_rows)
    : columns_(columns), lags_(std::max(lags, 0)), block_rows_(std::max(block_rows, 1)) {
    rows_.resize(lags_ + block_rows_, columns_);
    gamma_.assign(static_cast<std::size_t>(lags_), Eigen::MatrixXd::Zero(columns, columns));
}

void LaggedProducts::add_row(const double* row) {
    if (lags_ == 0) return;
    rows_.row(history_ + buffered_) = Eigen::Map<const Eigen::RowVectorXd>(row, columns_);
    if (++buffered_ == block_rows_) fold();
}

void LaggedProducts::fold() {
    if (buffered_ == 0) return;
    const auto block = rows_.middleRows(history_, buffered_);
    // Row i of the block pairs with the row l earlier, which is in the history for the first l rows.
    for (Eigen::Index l = 1; l <= lags_; ++l) {
        const Eigen::Index start = std::max<Eigen::Index>(0, l - history_);  // first block row that has a partner
        if (start >= buffered_) continue;
        const Eigen::Index count = buffered_ - start;
        gamma_[static_cast<std::size_t>(l - 1)].noalias() += block.middleRows(start, count).transpose() * rows_.middleRows(history_ + start - l, count);
    }
    // Keep the last L rows as the next block's history.
    const Eigen::Index total = history_ + buffered_;
    const Eigen::Index keep = std::min<Eigen::Index>(lags_, total);
    const Eigen::MatrixXd tail = rows_.middleRows(total - keep, keep);
    rows_.topRows(keep) = tail;
    history_ = keep;
    buffered_ = 0;
}

const std::vector<Eigen::MatrixXd>& LaggedProducts::gamma() {
    fold();
    return gamma_;
}

std::vector<double> residual_autocorrelation(const std::vector<Eigen::MatrixXd>& gamma, const Eigen::VectorXd& u, double gamma0) {
    std::vector<double> rho;
    if (!(gamma0 > 0.0)) return rho;
    for (const auto& g : gamma) rho.push_back(u.dot(g * u) / gamma0);
    return rho;
}

double long_run_variance_factor(const std::vector<Eigen::MatrixXd>& gamma, const Eigen::VectorXd& u, double gamma0) {
    const std::vector<double> rho = residual_autocorrelation(gamma, u, gamma0);
    const double lags = static_cast<double>(rho.size());
    double f = 1.0;
    for (std::size_t l = 1; l <= rho.size(); ++l) f += 2.0 * (1.0 - static_cast<double>(l) / (lags + 1.0)) * rho[l - 1];
    // Bartlett weights make the estimate a non-negative spectral estimate; a floor guards rounding.
    return std::max(f, 1e-3);
}

double bartlett_cross_sum(const Eigen::Ref<const Eigen::MatrixXd>& x, const Eigen::Ref<const Eigen::MatrixXd>& y, int lags) {
    const Eigen::Index n = x.rows();
    double s = x.cwiseProduct(y).sum();
    for (Eigen::Index l = 1; l <= lags && l < n; ++l) {
        const double w = 1.0 - static_cast<double>(l) / (lags + 1.0);
        s += w * (x.bottomRows(n - l).cwiseProduct(y.topRows(n - l)).sum() + x.topRows(n - l).cwiseProduct(y.bottomRows(n - l)).sum());
    }
    return s;
}

double bartlett_long_run_variance(const Eigen::Ref<const Eigen::VectorXd>& g, int lags) { return std::max(bartlett_cross_sum(g, g, lags), 0.0); }

int newey_west_lags(std::size_t rows) {
    return static_cast<int>(std::floor(4.0 * std::pow(static_cast<double>(rows) / 100.0, 2.0 / 9.0)));
}

}  // namespace jacobid::identify
