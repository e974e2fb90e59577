// SPDX-License-Identifier: MIT
#include "excite/motion_information.hpp"

#include <algorithm>

#include "excite/information_criterion.hpp"
#include "signal/baseline_response.hpp"
#include "signal/kernel_design_checked.hpp"

namespace jacobid::excite {

Eigen::MatrixXd motion_information(const robot::RobotModel& model, const SampledMotion& motion, const Eigen::VectorXd& noise_std,
                                   std::size_t max_rows) {
    const int n = model.joint_count(), p = model.parameter_count();
    const std::size_t first = motion.begin(), last = motion.end(), count = motion.counted();
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

Eigen::MatrixXd filtered_motion_information(const robot::RobotModel& model, const SampledMotion& motion, const Eigen::VectorXd& noise_std,
                                            double sample_period, double cutoff_hz, int order) {
    const int n = model.joint_count(), p = model.parameter_count();
    const std::size_t first = motion.begin();
    const auto count = static_cast<Eigen::Index>(motion.counted());
    const signal::ButterworthSos fp = signal::design_butterworth_or_throw(order, cutoff_hz, sample_period, "the prediction's decimation filter F_p");
    // One joint's rows at a time (samples x columns), the regressor evaluated again per joint: memory of one
    // joint's columns instead of all joints' (a 120 s log at 1 kHz: 50 MB instead of 300 MB).
    Eigen::MatrixXd Wj(count, p), Y(n, p);
    Eigen::VectorXd q(n), qd(n), qdd(n), filtered(count);
    std::vector<double> workspace;
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(p, p);
    for (int j = 0; j < n; ++j) {
        for (Eigen::Index i = 0; i < count; ++i) {
            const std::size_t s = first + static_cast<std::size_t>(i);
            for (int k = 0; k < n; ++k) {
                const auto u = static_cast<std::size_t>(k);
                q[k] = motion.q[u][s], qd[k] = motion.qd[u][s], qdd[k] = motion.qdd[u][s];
            }
            model.regressor(q.data(), qd.data(), qdd.data(), Y);
            Wj.row(i) = Y.row(j);
        }
        for (Eigen::Index c = 0; c < p; ++c) {
            signal::filtfilt_or_throw(fp, Wj.col(c).data(), filtered.data(), static_cast<std::size_t>(count), workspace);
            Wj.col(c) = filtered;
        }
        A.selfadjointView<Eigen::Lower>().rankUpdate(Wj.transpose(), 1.0 / (noise_std[j] * noise_std[j]));
    }
    return A.selfadjointView<Eigen::Lower>();
}

}  // namespace jacobid::excite
