// SPDX-License-Identifier: MIT
#include "payload/payload_rows.hpp"

#include <stdexcept>

namespace jacobid::payload {

PayloadRows::PayloadRows(int joints, Eigen::MatrixXd link_columns, Eigen::VectorXd theta, int lags, const StoredRows* reference)
    : joints_(joints), link_columns_(std::move(link_columns)), theta_(std::move(theta)), reference_(reference) {
    width_ = 10 + static_cast<int>(theta_.size()) + joints + 1;
    for (int j = 0; j < joints; ++j) {
        qr_.emplace_back(width_);
        lagged_.emplace_back(width_, lags);
    }
    row_.resize(width_);
}

void PayloadRows::row(const identify::DecimatedRow& r) {
    const Eigen::Index c = theta_.size();
    const StoredRows::Row* ref = nullptr;
    if (reference_) {
        if (next_ >= reference_->rows().size() || reference_->rows()[next_].sample != r.sample) {
            throw std::logic_error("payload: the unloaded run's pipeline has no row at the loaded run's sample (plans differ)");
        }
        ref = &reference_->rows()[next_++];
    }
    for (int j = 0; j < joints_; ++j) {
        row_.setZero();
        row_.head<10>() = link_columns_.transpose() * r.w.row(j).transpose();
        Eigen::VectorXd w = r.w.row(j).transpose();
        double y = r.y[j];
        if (ref) {
            w -= ref->w.row(j).transpose();
            y -= ref->y[j];
        }
        row_.segment(10, c) = w;
        row_[10 + c + j] = y;
        row_[width_ - 1] = y - w.dot(theta_);
        qr_[static_cast<std::size_t>(j)].add_row(row_.data());
        lagged_[static_cast<std::size_t>(j)].add_row(row_.data());
    }
}

identify::JointFactors PayloadRows::factors() {
    identify::JointFactors f;
    for (std::size_t j = 0; j < qr_.size(); ++j) {
        f.r.push_back(qr_[j].r());
        f.rows.push_back(qr_[j].rows());
        f.lagged.push_back(lagged_[j].gamma());
    }
    return f;
}

}  // namespace jacobid::payload
