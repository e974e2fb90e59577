// SPDX-License-Identifier: MIT
#include "excite/motion_information.hpp"

#include <algorithm>

#include "excite/information_criterion.hpp"

namespace jacobid::excite {

Eigen::MatrixXd motion_information(const robot::RobotModel& model, const SampledMotion& motion, const Eigen::VectorXd& noise_std,
                                   std::size_t max_rows) {
    const int n = model.joint_count(), p = model.parameter_count();
    const std::size_t last = motion.last == 0 ? motion.samples() : std::min(motion.last, motion.samples());
    const std::size_t first = std::min(motion.first, last), count = last - first;
    const std::size_t stride = std::max<std::size_t>(1, (count + max_rows - 1) / std::max<std::size_t>(1, max_rows));
    constexpr std::size_t kBatch = 256;  // samples stacked per rank update
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(p, p);
    Eigen::MatrixXd rows(static_cast<Eigen::Index>(kBatch) * n, p), Y(n, p);
    Eigen::VectorXd q(n), qd(n), qdd(n);
    std::size_t filled = 0;
    auto flush = [&] {
        if (filled == 0) return;
        A += information_matrix(rows.topRows(static_cast<Eigen::Index>(filled) * n), n, noise_std, static_cast<double>(stride));
        filled = 0;
    };
    for (std::size_t i = first; i < last; i += stride) {
        for (int j = 0; j < n; ++j) {
            const auto k = static_cast<std::size_t>(j);
            q[j] = motion.q[k][i], qd[j] = motion.qd[k][i], qdd[j] = motion.qdd[k][i];
        }
        model.regressor(q.data(), qd.data(), qdd.data(), Y);
        rows.middleRows(static_cast<Eigen::Index>(filled) * n, n) = Y;
        if (++filled == kBatch) flush();
    }
    flush();
    return A;
}

}  // namespace jacobid::excite
