// SPDX-License-Identifier: MIT
#pragma once
// Least squares that accumulates rows into a running triangular factor: [W Y] = Q R, only R (columns x
// columns) is kept. Memory is independent of the number of rows, so logs of any length fit, and R carries
// everything the LS solution and its statistics need: R^T R = [W Y]^T [W Y], the last diagonal entry is
// the residual norm, the last column's norm is ||Y||. Rows are buffered in blocks and folded in with a
// Householder QR of [R; block] (numerically as good as a QR of the whole W; no normal equations, whose
// squared condition number would cost digits).
#include <Eigen/Dense>
#include <cstddef>

namespace jacobid::identify {

class RunningQr {
public:
    explicit RunningQr(int columns = 0, int block_rows = 1024);

    int columns() const { return columns_; }
    std::size_t rows() const { return rows_; }
    // Appends one row of `columns` values.
    void add_row(const double* row);
    // Folds another triangular factor in (rows of a previously accumulated system, scaled by `scale`).
    void add_factor(const Eigen::MatrixXd& r, std::size_t rows, double scale = 1.0);
    // The upper triangular factor of everything added so far (columns x columns).
    const Eigen::MatrixXd& r();

private:
    void fold();

    int columns_;
    int block_rows_;
    std::size_t rows_ = 0;
    Eigen::Index buffered_ = 0;
    Eigen::MatrixXd r_;
    Eigen::MatrixXd block_;
    Eigen::MatrixXd stack_;
};

}  // namespace jacobid::identify
