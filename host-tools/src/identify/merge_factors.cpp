// SPDX-License-Identifier: MIT
#include "identify/merge_factors.hpp"

#include <fmt/core.h>

#include "core/errors.hpp"
#include "identify/running_qr.hpp"

namespace jacobid::identify {

void merge_factors(JointFactors& total, const JointFactors& part) {
    if (total.r.empty()) {
        total = part;
        return;
    }
    if (part.r.size() != total.r.size() || part.rows.size() != part.r.size()) {
        throw InputError(fmt::format("merging identification systems: {} joints and {} joints", total.r.size(), part.r.size()));
    }
    for (std::size_t j = 0; j < total.r.size(); ++j) {
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
