// SPDX-License-Identifier: MIT
#include "identify/pipeline/row_collector.hpp"

#include <algorithm>

namespace jacobid::identify {

RowCollector::RowCollector(std::size_t joints, std::size_t samples, RowCollectorSettings settings)
    : settings_(settings), w_(joints), y_(joints), states_(joints), filtered_(joints, std::vector<double>(settings.filtered_torque ? samples : 0, 0.0)) {}

void RowCollector::row(const DecimatedRow& r) {
    if (!complete_) return;
    parameters_ = static_cast<std::size_t>(r.w.cols());
    if (settings_.max_values > 0 && (samples_.size() + 1) * w_.size() * parameters_ > settings_.max_values) {
        complete_ = false;  // too many rows to hold: release what was kept (`= {}` would keep the capacity)
        std::vector<std::size_t>().swap(samples_);
        std::vector<double>().swap(t_);
        for (auto* per_joint : {&w_, &y_, &states_}) {
            for (auto& v : *per_joint) std::vector<double>().swap(v);
        }
        return;
    }
    samples_.push_back(r.sample);
    if (settings_.torque_and_states) t_.push_back(r.t);
    for (std::size_t j = 0; j < w_.size(); ++j) {
        const auto je = static_cast<Eigen::Index>(j);
        for (std::size_t p = 0; p < parameters_; ++p) w_[j].push_back(r.w(je, static_cast<Eigen::Index>(p)));
        if (settings_.torque_and_states) {
            y_[j].push_back(r.y[je]);
            states_[j].insert(states_[j].end(), {r.q[je], r.qd[je], r.qdd[je]});
        }
    }
}

void RowCollector::filtered_torque(std::size_t first, std::size_t count, const std::vector<const double*>& tau) {
    if (!settings_.filtered_torque) return;
    for (std::size_t j = 0; j < tau.size(); ++j) std::copy(tau[j], tau[j] + count, filtered_[j].begin() + static_cast<std::ptrdiff_t>(first));
    covered_from_ = std::min(covered_from_, first);
    covered_to_ = std::max(covered_to_, first + count);
}

}  // namespace jacobid::identify
