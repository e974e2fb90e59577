// SPDX-License-Identifier: MIT
#pragma once
// What one pipeline run folds into the least squares, kept for a second look (a RowSink, pipeline.hpp):
// every decimated row's full-rate sample index and W (per joint, row-major), optionally its Y and the
// unfiltered estimates it was built from, and the full-rate torque after F_p that Y is sampled from. The
// torque-delay search refits shifted torques from it (identify/friction/torque_delay.cpp); diagnose locates and
// explains the residual with it (diagnose/decimated_rows.hpp).
#include <cstddef>
#include <limits>
#include <vector>

#include "identify/pipeline/pipeline.hpp"

namespace jacobid::identify {

struct RowCollectorSettings {
    bool torque_and_states = false;  // keep each row's Y, time and (q, qd, qdd) as well
    bool filtered_torque = true;     // keep the full-rate torque after F_p (joints x log samples)
    // Most values of W to hold (rows x joints x parameters); past it the rows stop being kept and complete()
    // is false. 0: no limit.
    std::size_t max_values = 0;
};

class RowCollector final : public RowSink {
public:
    RowCollector(std::size_t joints, std::size_t samples, RowCollectorSettings settings = {});

    void row(const DecimatedRow& r) override;
    void filtered_torque(std::size_t first, std::size_t count, const std::vector<const double*>& tau) override;

    // False when max_values stopped the rows from being kept (none are then usable).
    bool complete() const { return complete_; }
    std::size_t rows() const { return samples_.size(); }
    std::size_t parameters() const { return parameters_; }
    std::size_t joints() const { return w_.size(); }
    const std::vector<std::size_t>& samples() const { return samples_; }
    const std::vector<double>& times() const { return t_; }
    const std::vector<double>& w(std::size_t joint) const { return w_[joint]; }          // rows x parameters, row-major
    const std::vector<double>& y(std::size_t joint) const { return y_[joint]; }          // rows
    const std::vector<double>& states(std::size_t joint) const { return states_[joint]; }  // rows x (q, qd, qdd), row-major
    // Full length; only [covered_from(), covered_to()) was filled (the valid derivative range), 0 elsewhere.
    std::vector<std::vector<double>>& filtered_torque() { return filtered_; }
    const std::vector<std::vector<double>>& filtered_torque() const { return filtered_; }
    std::size_t covered_from() const { return covered_from_; }
    std::size_t covered_to() const { return covered_to_; }

private:
    RowCollectorSettings settings_;
    std::vector<std::vector<double>> w_, y_, states_, filtered_;
    std::vector<std::size_t> samples_;
    std::vector<double> t_;
    std::size_t parameters_ = 0;
    std::size_t covered_from_ = std::numeric_limits<std::size_t>::max(), covered_to_ = 0;
    bool complete_ = true;
};

}  // namespace jacobid::identify
