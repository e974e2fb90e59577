// SPDX-License-Identifier: MIT
#include "sim/reference_checks.hpp"

#include <fmt/core.h>

#include <cmath>
#include <set>
#include <string>

#include "core/errors.hpp"

namespace jacobid::sim {

void require_reference_columns(const io::CsvTable& table, int joints) {
    std::set<std::string> expected{"t"};
    for (int j = 1; j <= joints; ++j) {
        for (const char* kind : {"q", "qd", "qdd"}) expected.insert(fmt::format("{}{}", kind, j));
    }
    const std::string layout = fmt::format("the robot has {} joint{}: expected the columns t, q1..q{n}, qd1..qd{n}, qdd1..qdd{n}", joints,
                                           joints == 1 ? "" : "s", fmt::arg("n", joints));
    const auto& header = table.header();
    for (std::size_t c = 0; c < header.size(); ++c) {
        if (expected.count(header[c]) == 0) {
            throw InputError(fmt::format("{}:1: column {} '{}' is not read by the simulator ({}; a table for another robot?)", table.source(), c + 1,
                                         io::printable_cell(header[c]), layout));
        }
    }
    for (const std::string& name : expected) {
        if (!table.has_column(name)) throw InputError(fmt::format("{}:1: no column '{}' ({})", table.source(), name, layout));
    }
}

void require_plausible_reference_step(const io::CsvTable& table, double step) {
    if (step >= kMinReferenceStep && step <= kMaxReferenceStep) return;
    throw InputError(fmt::format("{}: line {}, column t: time step {:g} s, expected {:g} .. {:g} s (is t in seconds?)", table.source(),
                                 table.line_of_row(1), step, kMinReferenceStep, kMaxReferenceStep));
}

void require_reference_within_limits(const io::CsvTable& table, const std::vector<std::vector<double>>& q,
                                     const std::vector<std::optional<io::PositionBounds>>& limits) {
    for (std::size_t j = 0; j < q.size() && j < limits.size(); ++j) {
        if (!limits[j]) continue;
        for (std::size_t i = 0; i < q[j].size(); ++i) {
            const double v = q[j][i];
            if (v >= limits[j]->lower && v <= limits[j]->upper) continue;
            throw InputError(fmt::format("{}: line {}, column q{}: position {:.10g} is outside {}'s limits [{:g}, {:g}] of the robot description",
                                         table.source(), table.line_of_row(i), j + 1, v, limits[j]->joint, limits[j]->lower, limits[j]->upper));
        }
    }
}

namespace {

// Whether `moved` equals `integrated` within 5 % of the step's motion `scale` plus 1e-6 (rounded cells).
bool agrees(double moved, double integrated, double scale) { return std::abs(moved - integrated) <= 0.05 * scale + 1e-6; }

}  // namespace

void require_consistent_derivatives(const io::CsvTable& table, double step, const std::vector<std::vector<double>>& q,
                                    const std::vector<std::vector<double>>& qd, const std::vector<std::vector<double>>& qdd) {
    const double h = step;
    for (std::size_t j = 0; j < q.size(); ++j) {
        for (std::size_t i = 1; i < q[j].size(); ++i) {
            const double v0 = qd[j][i - 1], v1 = qd[j][i], a0 = qdd[j][i - 1], a1 = qdd[j][i];
            const double dq = q[j][i] - q[j][i - 1], dq_integrated = h / 2 * (v0 + v1) + h * h / 12 * (a0 - a1);
            if (!agrees(dq, dq_integrated, std::abs(dq) + h / 2 * (std::abs(v0) + std::abs(v1)) + h * h / 12 * (std::abs(a0) + std::abs(a1)))) {
                throw InputError(fmt::format("{}: line {}, columns q{j}, qd{j}, qdd{j}: q{j} moves by {:.6g} from the line before, its velocity and "
                                             "acceleration integrate to {:.6g}: qd{j} and qdd{j} must be q{j}'s derivatives in rad/s and rad/s^2 (m for a "
                                             "prismatic joint)",
                                             table.source(), table.line_of_row(i), dq, dq_integrated, fmt::arg("j", j + 1)));
            }
            const double dv = v1 - v0, dv_integrated = h / 2 * (a0 + a1);
            if (!agrees(dv, dv_integrated, std::abs(dv) + h / 2 * (std::abs(a0) + std::abs(a1)))) {
                throw InputError(fmt::format("{}: line {}, columns qd{j}, qdd{j}: qd{j} changes by {:.6g} from the line before, its acceleration "
                                             "integrates to {:.6g}: qdd{j} must be qd{j}'s derivative in rad/s^2 (m/s^2 for a prismatic joint)",
                                             table.source(), table.line_of_row(i), dv, dv_integrated, fmt::arg("j", j + 1)));
            }
        }
    }
}

}  // namespace jacobid::sim
