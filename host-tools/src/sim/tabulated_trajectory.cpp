// SPDX-License-Identifier: MIT
#include "sim/tabulated_trajectory.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>

#include "core/errors.hpp"
#include "sim/reference_checks.hpp"

namespace jacobid::sim {

TabulatedTrajectory::TabulatedTrajectory(const io::CsvTable& table, int joints, const std::vector<std::optional<io::PositionBounds>>& limits) {
    require_reference_columns(table, joints);
    t_ = table.column("t");
    if (t_.size() < 2) throw InputError(fmt::format("{}: {} rows: a trajectory needs at least 2", table.source(), t_.size()));
    step_ = t_[1] - t_[0];
    require_plausible_reference_step(table, step_);
    if (t_[0] != 0.0) throw InputError(fmt::format("{}: line {}, column t: {} s, expected the trajectory to start at 0", table.source(), table.line_of_row(0), t_[0]));
    for (std::size_t i = 1; i < t_.size(); ++i) {
        const double dt = t_[i] - t_[i - 1];
        if (!(dt > 0.0) || std::abs(dt - step_) > 1e-6 * step_ + 1e-9) {
            throw InputError(fmt::format("{}: line {}, column t: step {} s, expected a uniform step of {} s", table.source(), table.line_of_row(i), dt, step_));
        }
    }
    for (int j = 1; j <= joints; ++j) {
        q_.push_back(table.column(fmt::format("q{}", j)));
        qd_.push_back(table.column(fmt::format("qd{}", j)));
        qdd_.push_back(table.column(fmt::format("qdd{}", j)));
    }
    // Repeating must not jump: the last row is the first row again.
    const std::size_t last = t_.size() - 1;
    for (int j = 0; j < joints; ++j) {
        const auto k = static_cast<std::size_t>(j);
        const double jumps[3] = {q_[k][last] - q_[k][0], qd_[k][last] - qd_[k][0], qdd_[k][last] - qdd_[k][0]};
        const char* names[3] = {"q", "qd", "qdd"};
        for (int v = 0; v < 3; ++v) {
            if (std::abs(jumps[v]) > 1e-6) {
                throw InputError(fmt::format("{}: line {}, column {}{}: the trajectory must end where it starts to repeat ({:+.3g} from line 2)", table.source(),
                                             table.line_of_row(last), names[v], j + 1, jumps[v]));
            }
        }
    }
    require_reference_within_limits(table, q_, limits);
    require_consistent_derivatives(table, step_, q_, qd_, qdd_);
}

std::vector<double> TabulatedTrajectory::start() const {
    std::vector<double> q;
    for (const auto& column : q_) q.push_back(column.front());
    return q;
}

void TabulatedTrajectory::evaluate(double t, ReferenceSample& out) const {
    t = std::fmod(t, length());
    if (t < 0.0) t += length();
    const std::size_t last = t_.size() - 1;
    const std::size_t i = std::min(static_cast<std::size_t>(t / step_), last - 1);
    const double h = step_, s = std::clamp((t - t_[i]) / h, 0.0, 1.0);
    // Quintic Hermite basis on [0, 1] (position, velocity, acceleration at both ends).
    const double s2 = s * s, s3 = s2 * s, s4 = s3 * s, s5 = s4 * s;
    const double h0 = 1 - 10 * s3 + 15 * s4 - 6 * s5, h1 = s - 6 * s3 + 8 * s4 - 3 * s5, h2 = 0.5 * (s2 - 3 * s3 + 3 * s4 - s5);
    const double h3 = 10 * s3 - 15 * s4 + 6 * s5, h4 = -4 * s3 + 7 * s4 - 3 * s5, h5 = 0.5 * (s3 - 2 * s4 + s5);
    const double d0 = -30 * s2 + 60 * s3 - 30 * s4, d1 = 1 - 18 * s2 + 32 * s3 - 15 * s4, d2 = 0.5 * (2 * s - 9 * s2 + 12 * s3 - 5 * s4);
    const double d3 = 30 * s2 - 60 * s3 + 30 * s4, d4 = -12 * s2 + 28 * s3 - 15 * s4, d5 = 0.5 * (3 * s2 - 8 * s3 + 5 * s4);
    const double e0 = -60 * s + 180 * s2 - 120 * s3, e1 = -36 * s + 96 * s2 - 60 * s3, e2 = 0.5 * (2 - 18 * s + 36 * s2 - 20 * s3);
    const double e3 = 60 * s - 180 * s2 + 120 * s3, e4 = -24 * s + 84 * s2 - 60 * s3, e5 = 0.5 * (6 * s - 24 * s2 + 20 * s3);
    const std::size_t n = q_.size();
    out.q.resize(n), out.qd.resize(n), out.qdd.resize(n);
    for (std::size_t j = 0; j < n; ++j) {
        const double p0 = q_[j][i], v0 = qd_[j][i] * h, a0 = qdd_[j][i] * h * h;
        const double p1 = q_[j][i + 1], v1 = qd_[j][i + 1] * h, a1 = qdd_[j][i + 1] * h * h;
        out.q[j] = h0 * p0 + h1 * v0 + h2 * a0 + h3 * p1 + h4 * v1 + h5 * a1;
        out.qd[j] = (d0 * p0 + d1 * v0 + d2 * a0 + d3 * p1 + d4 * v1 + d5 * a1) / h;
        out.qdd[j] = (e0 * p0 + e1 * v0 + e2 * a0 + e3 * p1 + e4 * v1 + e5 * a1) / (h * h);
    }
}

}  // namespace jacobid::sim
