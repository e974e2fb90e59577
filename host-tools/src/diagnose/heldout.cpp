// SPDX-License-Identifier: MIT
#include "diagnose/heldout.hpp"

#include <cmath>
#include <limits>

namespace jacobid::diagnose {

double HeldOut::rms(const std::vector<int>& columns, int joint) const {
    const std::vector<double> unit;
    const std::vector<double>& predict_weights = joint < 0 ? weight2_ : unit;
    double sse = 0.0, rows = 0.0;
    auto add = [&](const BlockedGrams& held, int block, const SubsetFit& fit) {
        const GramSums h = held.sum(columns, predict_weights, block, false, joint);
        sse += prediction_sse(h, fit.x);
        rows += h.rows;
    };
    if (validation_) {
        const SubsetFit fit = solve_subset(train_.sum(columns, weight2_, -1, false));
        if (!fit.ok) return std::numeric_limits<double>::quiet_NaN();
        add(*validation_, -1, fit);
    } else {
        for (int b = 0; b < train_.blocks(); ++b) {
            const SubsetFit fit = solve_subset(train_.sum(columns, weight2_, b, true));
            if (!fit.ok) return std::numeric_limits<double>::quiet_NaN();
            add(train_, b, fit);
        }
    }
    return rows > 0.0 ? std::sqrt(sse / rows) : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace jacobid::diagnose
