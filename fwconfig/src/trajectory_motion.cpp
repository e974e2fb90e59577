// SPDX-License-Identifier: MIT
#include "jacobid/fwconfig/trajectory_motion.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace jacobid::firmware {
namespace {

// One commanded state: a table row, or the end of the ramp-in (row 0's pose at rest), on a pass.
struct Commanded {
    std::size_t row = 0;
    bool at_rest = false;  // the ramp-in's last command: row 0's position with zero velocity
    bool wrapped = false;  // on the second pass, after the wrap from the last row
};

// The distinct steps the player commands, in order: the first pass (from the ramp-in's end in position
// mode, from row 0 in torque mode) and, with repeat > 1, the wrap into the next pass and its first steps.
// Later passes repeat these steps exactly.
std::vector<Commanded> commanded_states(const PlaybackConfig& config, std::size_t joints) {
    const std::size_t n = config.rows.size();
    std::vector<Commanded> states;
    const bool ramp = config.mode == hal::CommandMode::Position;
    states.push_back({0, ramp, false});
    for (std::size_t r = 1; r < n; ++r) states.push_back({r, false, false});
    if (config.repeat > 1) {
        for (std::size_t r = next_pass_row(config, joints); r < n && states.size() < n + 3; ++r) states.push_back({r, false, true});
    }
    return states;
}

double velocity_of(const PlaybackConfig& config, const Commanded& s, std::size_t j) { return s.at_rest ? 0.0 : config.rows[s.row].qd[j]; }
double position_of(const PlaybackConfig& config, const Commanded& s, std::size_t j) { return config.rows[s.row].q[j]; }

std::string line_of(const PlaybackConfig& config, const Commanded& s) {
    const std::size_t line = config.rows[s.row].line;
    std::string where = line != 0 ? fmt::format("line {}", line) : fmt::format("row {}", s.row + 1);
    if (s.at_rest) where += " at rest (the end of the ramp-in)";
    if (s.wrapped) where += " of the next pass";
    return where;
}

// What to change, when the step involves the start or the wrap.
std::string hint(const PlaybackConfig& config, std::size_t joints, const Commanded& first, const Commanded& last) {
    if (last.wrapped) {
        const std::size_t end = config.rows.size() - 1;
        return fmt::format("; this is the wrap from the table's last row ({}) to its next pass (repeat: {}), and the table does not join its "
                           "start smoothly: make it end on its first row's pose with the first row's velocity (jacobid excite's periodic "
                           "tables do), or set repeat: 1",
                           line_of(config, Commanded{end, false, false}), config.repeat) +
               (next_pass_row(config, joints) == 1 ? " (it ends on its first row's pose, so the next pass starts at its second row)" : "");
    }
    if (first.at_rest) return "; the ramp-in ends at rest on the first row, so the table must start at rest (zero velocity, then steps within the acceleration limit)";
    return "";
}

class MotionCheck {
public:
    MotionCheck(const PlaybackConfig& config, std::size_t joints, double ts) : c_(config), joints_(joints), ts_(ts) {}

    // The step a -> b of joint j: its velocity, its velocity column's change, and the two against each other.
    std::string step(const Commanded& a, const Commanded& b, std::size_t j) const {
        const double v_limit = c_.velocity_limit[j], a_limit = c_.acceleration_limit[j];
        const double dq = position_of(c_, b, j) - position_of(c_, a, j);
        const double qd_a = velocity_of(c_, a, j), qd_b = velocity_of(c_, b, j);
        if (std::abs(dq) > v_limit * ts_ * (1.0 + kMotionLimitTolerance) + 2.0 * kTablePositionResolution) {
            return fail(a, b, j, fmt::format("the position steps {:.4g} rad from {}, {:.4g} rad/s at {:.6g} Hz, beyond the velocity limit {:.6g} rad/s "
                                                "(trajectory.joints[{}].velocity, +{:g} %)",
                                                dq, line_of(c_, a), dq / ts_, 1.0 / ts_, v_limit, j, 100.0 * kMotionLimitTolerance));
        }
        const double dqd = qd_b - qd_a;
        if (std::abs(dqd) > a_limit * ts_ * (1.0 + kMotionLimitTolerance) + 2.0 * kTablePositionResolution) {
            return fail(a, b, j, fmt::format("the velocity column steps {:.4g} rad/s from {}, {:.4g} rad/s^2 at {:.6g} Hz, beyond the acceleration "
                                                "limit {:.6g} rad/s^2 (trajectory.joints[{}].acceleration, +{:g} %)",
                                                dqd, line_of(c_, a), dqd / ts_, 1.0 / ts_, a_limit, j, 100.0 * kMotionLimitTolerance));
        }
        // A motion within the acceleration limit that has velocities qd_a and qd_b at the two rows moves,
        // on average over the row period, at a velocity within a_limit Ts / 2 of [qd_a, qd_b].
        const double slack = 0.5 * a_limit * ts_ * (1.0 + kMotionLimitTolerance) + kMotionLimitTolerance * v_limit + 2.0 * kTablePositionResolution / ts_;
        const double mean = dq / ts_;
        if (mean < std::min(qd_a, qd_b) - slack || mean > std::max(qd_a, qd_b) + slack) {
            return fail(a, b, j, fmt::format("the position step from {} moves at {:.4g} rad/s, but the velocity column says {:.4g} and {:.4g} rad/s "
                                                "(at most {:.3g} rad/s apart within the acceleration limit): q{} and qd{} do not describe one motion "
                                                "(a velocity in other units, or another joint's?)",
                                                line_of(c_, a), mean, qd_a, qd_b, slack, j + 1, j + 1));
        }
        return {};
    }

    // The positions a -> b -> c of joint j: their second difference over the row period squared.
    std::string curvature(const Commanded& a, const Commanded& b, const Commanded& c, std::size_t j) const {
        const double a_limit = c_.acceleration_limit[j];
        const double d2q = position_of(c_, c, j) - 2.0 * position_of(c_, b, j) + position_of(c_, a, j);
        if (std::abs(d2q) > a_limit * ts_ * ts_ * (1.0 + kMotionLimitTolerance) + 4.0 * kTablePositionResolution) {
            return fail(a, c, j, fmt::format("the positions of {}, {} and {} accelerate at {:.4g} rad/s^2 at {:.6g} Hz, beyond the acceleration limit "
                                                "{:.6g} rad/s^2 (trajectory.joints[{}].acceleration, +{:g} %)",
                                                line_of(c_, a), line_of(c_, b), line_of(c_, c), d2q / (ts_ * ts_), 1.0 / ts_, a_limit, j,
                                                100.0 * kMotionLimitTolerance));
        }
        return {};
    }

private:
    // Named at the step's last row, with what to change when the step is the start or the wrap.
    std::string fail(const Commanded& first, const Commanded& last, std::size_t j, const std::string& what) const {
        return fmt::format("{}: joint {}: {}{}", table_location(c_, last.row), j + 1, what, hint(c_, joints_, first, last));
    }

    const PlaybackConfig& c_;
    std::size_t joints_;
    double ts_;
};

}  // namespace

std::size_t next_pass_row(const PlaybackConfig& config, std::size_t joints) noexcept {
    if (config.rows.empty()) return 0;
    const TrajectoryRow& first = config.rows.front();
    const TrajectoryRow& last = config.rows.back();
    for (std::size_t j = 0; j < joints; ++j) {
        if (!(std::abs(first.q[j] - last.q[j]) <= kTablePositionResolution)) return 0;
    }
    return 1;
}

std::string table_location(const PlaybackConfig& config, std::size_t row) {
    const std::string file = config.file.empty() ? "trajectory table" : config.file;
    const std::size_t line = row < config.rows.size() ? config.rows[row].line : 0;
    return line != 0 ? fmt::format("{}:{}", file, line) : fmt::format("{} row {}", file, row + 1);
}

std::string check_trajectory_motion(const PlaybackConfig& config, std::size_t joints, double sample_period) {
    if (config.rows.size() < 2 || !(sample_period > 0.0)) return "trajectory: a table of at least two rows and a sample period > 0 are needed";
    const MotionCheck check(config, joints, sample_period);
    const std::vector<Commanded> states = commanded_states(config, joints);
    for (std::size_t k = 1; k < states.size(); ++k) {
        for (std::size_t j = 0; j < joints; ++j) {
            if (std::string why = check.step(states[k - 1], states[k], j); !why.empty()) return why;
            if (k < 2) continue;
            if (std::string why = check.curvature(states[k - 2], states[k - 1], states[k], j); !why.empty()) return why;
        }
    }
    return {};
}

}  // namespace jacobid::firmware
