// SPDX-License-Identifier: MIT
#include "diagnose/blocked_grams.hpp"

#include <algorithm>
#include <cmath>

namespace jacobid::diagnose {

BlockedGrams::BlockedGrams(const DecimatedRows& rows, int blocks) : w_(rows.w), blocks_(std::max(1, blocks)) {
    const auto m = static_cast<Eigen::Index>(rows.rows());
    for (int b = 0; b <= blocks_; ++b) bounds_.push_back(m * b / blocks_);
    g_.resize(w_.size());
    for (std::size_t j = 0; j < w_.size(); ++j) {
        for (int b = 0; b < blocks_; ++b) {
            const auto rows_b = w_[j].middleRows(bounds_[static_cast<std::size_t>(b)], bounds_[static_cast<std::size_t>(b) + 1] - bounds_[static_cast<std::size_t>(b)]);
            g_[j].push_back(rows_b.transpose() * rows_b);
        }
    }
    set_y(rows.y);
}

void BlockedGrams::set_y(const std::vector<Eigen::VectorXd>& y) {
    b_.assign(w_.size(), {});
    yy_.assign(w_.size(), {});
    for (std::size_t j = 0; j < w_.size(); ++j) {
        for (int b = 0; b < blocks_; ++b) {
            const Eigen::Index r0 = bounds_[static_cast<std::size_t>(b)], n = bounds_[static_cast<std::size_t>(b) + 1] - r0;
            b_[j].push_back(w_[j].middleRows(r0, n).transpose() * y[j].segment(r0, n));
            yy_[j].push_back(y[j].segment(r0, n).squaredNorm());
        }
    }
}

GramSums BlockedGrams::sum(const std::vector<int>& columns, const std::vector<double>& weight2, int block, bool exclude, int joint) const {
    const auto k = static_cast<Eigen::Index>(columns.size());
    GramSums s;
    s.G = Eigen::MatrixXd::Zero(k, k);
    s.b = Eigen::VectorXd::Zero(k);
    for (std::size_t j = 0; j < w_.size(); ++j) {
        if (joint >= 0 && static_cast<int>(j) != joint) continue;
        const double wj = weight2.empty() ? 1.0 : weight2[j];
        for (int b = 0; b < blocks_; ++b) {
            const bool use = block < 0 || (exclude ? b != block : b == block);
            if (!use) continue;
            const auto bs = static_cast<std::size_t>(b);
            s.G += wj * g_[j][bs](columns, columns);
            s.b += wj * b_[j][bs](columns);
            s.yy += wj * yy_[j][bs];
            s.rows += static_cast<double>(bounds_[bs + 1] - bounds_[bs]);
        }
    }
    return s;
}

}  // namespace jacobid::diagnose
