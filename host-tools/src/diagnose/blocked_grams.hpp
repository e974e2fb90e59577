// SPDX-License-Identifier: MIT
#pragma once
// Normal equations (identify/solve/normal_equations.hpp) of the decimated rows, kept per joint and per contiguous block of time: G = W^T W,
// b = W^T Y, yy = Y^T Y over every catalogue column. Any subset of columns, any joint weighting and any
// split into fitted and held-out blocks (blocked cross-validation) is then a small dense solve, so the
// stepwise selection can try hundreds of candidate models without touching the rows again.
#include <Eigen/Core>
#include <vector>

#include "diagnose/decimated_rows.hpp"
#include "identify/solve/normal_equations.hpp"

namespace jacobid::diagnose {

using identify::GramSums;
using identify::prediction_sse;
using identify::solve_subset;
using identify::SubsetFit;

class BlockedGrams {
public:
    BlockedGrams(const DecimatedRows& rows, int blocks);
    // Replaces Y (e.g. re-sampled for a torque delay); W is unchanged.
    void set_y(const std::vector<Eigen::VectorXd>& y);
    int blocks() const { return blocks_; }
    int joints() const { return static_cast<int>(w_.size()); }
    // Sums over joints weighted by weight2[j] (squared row weights; empty: 1) and over blocks: all blocks
    // when `block` < 0; with exclude, all but `block`; otherwise only `block`. joint >= 0: that joint only.
    GramSums sum(const std::vector<int>& columns, const std::vector<double>& weight2, int block, bool exclude, int joint = -1) const;

private:
    const std::vector<Eigen::MatrixXd>& w_;
    int blocks_;
    std::vector<Eigen::Index> bounds_;  // block b: rows [bounds_[b], bounds_[b + 1])
    std::vector<std::vector<Eigen::MatrixXd>> g_;  // [joint][block]
    std::vector<std::vector<Eigen::VectorXd>> b_;
    std::vector<std::vector<double>> yy_;
};

}  // namespace jacobid::diagnose
