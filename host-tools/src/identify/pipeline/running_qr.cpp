// SPDX-License-Identifier: MIT
#include "identify/pipeline/running_qr.hpp"

namespace jacobid::identify {

RunningQr::RunningQr(int columns, int block_rows)
    : columns_(columns),
      block_rows_(block_rows),
      r_(Eigen::MatrixXd::Zero(columns, columns)),
      block_(block_rows, columns),
      stack_(columns + block_rows, columns) {}

void RunningQr::add_row(const double* row) {
    for (int c = 0; c < columns_; ++c) block_(buffered_, c) = row[c];
    ++buffered_;
    ++rows_;
    if (buffered_ == block_rows_) fold();
}

void RunningQr::add_factor(const Eigen::MatrixXd& r, std::size_t rows, double scale) {
    fold();
    if (stack_.rows() < 2 * columns_) stack_.resize(2 * columns_, columns_);
    stack_.topRows(columns_) = r_;
    stack_.middleRows(columns_, columns_) = scale * r;
    Eigen::Ref<Eigen::MatrixXd> view = stack_.topRows(2 * columns_);
    Eigen::HouseholderQR<Eigen::Ref<Eigen::MatrixXd>> qr(view);
    r_ = qr.matrixQR().topRows(columns_).triangularView<Eigen::Upper>();
    rows_ += rows;
}

void RunningQr::fold() {
    if (buffered_ == 0) return;
    const Eigen::Index n = columns_ + buffered_;
    if (stack_.rows() < n) stack_.resize(n, columns_);
    stack_.topRows(columns_) = r_;
    stack_.middleRows(columns_, buffered_) = block_.topRows(buffered_);
    Eigen::Ref<Eigen::MatrixXd> view = stack_.topRows(n);
    Eigen::HouseholderQR<Eigen::Ref<Eigen::MatrixXd>> qr(view);  // in place: no copy of the stack
    r_ = qr.matrixQR().topRows(columns_).triangularView<Eigen::Upper>();
    buffered_ = 0;
}

const Eigen::MatrixXd& RunningQr::r() {
    fold();
    return r_;
}

}  // namespace jacobid::identify
