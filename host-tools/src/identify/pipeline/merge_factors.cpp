// SPDX-License-Identifier: MIT
#include "identify/pipeline/merge_factors.hpp"

#include <fmt/core.h>

#include "core/errors.hpp"
#include "identify/pipeline/running_qr.hpp"

namespace jacobid::identify {

void merge_factors(JointFactors& total, const JointFactors& part) {
    if (total.r.empty()) {
        total = part;
        return;
    }
    if (part.r.size() != total.r.size() || part.rows.size() != part.r.size()) {
        throw InputError(fmt::format("merging identification systems: {} joints and {} joints", total.r.size(), part.r.size()));
    }
    // Lagged products add up (no lag crosses the boundary between the systems); if either system has
    // none, the merged one has none.
    bool lagged = total.lagged.size() == total.r.size() && part.lagged.size() == part.r.size();
    for (std::size_t j = 0; lagged && j < total.r.size(); ++j) lagged = total.lagged[j].size() == part.lagged[j].size();
    if (!lagged) total.lagged.clear();
    for (std::size_t j = 0; j < total.r.size(); ++j) {
        if (lagged) {
            for (std::size_t l = 0; l < total.lagged[j].size(); ++l) total.lagged[j][l] += part.lagged[j][l];
        }
        const Eigen::Index n = total.r[j].cols();
        if (part.r[j].cols() != n || part.r[j].rows() != n || total.r[j].rows() != n) {
            throw InputError(fmt::format("merging identification systems: joint {} has {} and {} columns", j + 1, n, part.r[j].cols()));
        }
        RunningQr qr(static_cast<int>(n));
        qr.add_factor(total.r[j], total.rows[j]);
        qr.add_factor(part.r[j], part.rows[j]);
        total.r[j] = qr.r();
        total.rows[j] = qr.rows();
    }
}

}  // namespace jacobid::identify
