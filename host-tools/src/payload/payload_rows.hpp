// SPDX-License-Identifier: MIT
#pragma once
// The payload's equations, one per joint and decimated row of the pipeline (identify/pipeline/pipeline.hpp), folded
// into per-joint running QR factors (and lagged products, for identify's joint-HAC std) over the columns
//     [ W_j K_L (10) | W_j (c) | y_j e_j (joints) | y_j - W_j theta ]
// K_L: the regrouping's columns of the last link's ten standard parameters (a payload fixed to the last link adds
// to them); theta: the arm's base parameters, held. With the unloaded run's rows at the same samples (its
// pipeline on the same grid and plan, time_alignment.hpp), its residual against the arm is subtracted:
//     [ W_j K_L | W_j - W'_j | (y_j - y'_j) e_j | (y_j - W_j theta) - (y'_j - W'_j theta) ]
// so that what the arm's model lacks cancels where the motions agree, and the arm's model covers where they
// differ (the tracking error changes with the load). The middle blocks are never solved for: they are what the
// payload estimate's sensitivity to the arm's parameters (minus the second block) and to joint j's drive gain (a
// relative error scales y_j) is computed from.
#include <Eigen/Core>
#include <vector>

#include "identify/solve/least_squares.hpp"
#include "identify/pipeline/pipeline.hpp"
#include "identify/solve/residual_correlation.hpp"
#include "identify/pipeline/running_qr.hpp"

namespace jacobid::payload {

// The unloaded run's decimated rows, kept (a few thousand rows of W: small beside the full-rate log).
class StoredRows final : public identify::RowSink {
public:
    struct Row {
        std::size_t sample;
        Eigen::MatrixXd w;
        Eigen::VectorXd y;
    };
    void row(const identify::DecimatedRow& r) override { rows_.push_back({r.sample, r.w, r.y}); }
    const std::vector<Row>& rows() const { return rows_; }

private:
    std::vector<Row> rows_;
};

class PayloadRows final : public identify::RowSink {
public:
    // link_columns: c x 10; theta: c; reference: the unloaded run's rows (null: none). std::logic_error when a
    // row's sample has no reference row (the two pipelines did not run on the same plan).
    PayloadRows(int joints, Eigen::MatrixXd link_columns, Eigen::VectorXd theta, int lags, const StoredRows* reference = nullptr);
    void row(const identify::DecimatedRow& r) override;
    identify::JointFactors factors();

    int arm_columns() const { return static_cast<int>(theta_.size()); }
    int width() const { return width_; }

private:
    int joints_, width_;
    Eigen::MatrixXd link_columns_;
    Eigen::VectorXd theta_;
    const StoredRows* reference_;
    std::size_t next_ = 0;
    std::vector<identify::RunningQr> qr_;
    std::vector<identify::LaggedProducts> lagged_;
    Eigen::VectorXd row_;
};

}  // namespace jacobid::payload
