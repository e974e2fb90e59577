// SPDX-License-Identifier: MIT
#include "identify/plan/log_columns.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <array>

#include "core/errors.hpp"
#include "io/printable_text.hpp"
#include "io/time_axis.hpp"

namespace jacobid::identify {

std::optional<io::PositionBounds> position_bounds(const robot::RobotDescription& robot, std::size_t j) {
    const robot::JointDescription& joint = robot.joints[j];
    if (!joint.limits_given || !(joint.upper_limit > joint.lower_limit)) return std::nullopt;
    return io::PositionBounds{joint.lower_limit, joint.upper_limit, fmt::format("joint {} ({})", j + 1, joint.name)};
}

std::array<std::string, 2> reference_column_names(std::size_t j) {
    return {"q_ref" + std::to_string(j + 1), "qd_ref" + std::to_string(j + 1)};
}

namespace {

// Every torque exactly 0 in every row (a log whose efforts were all null, written as 0) leaves nothing to
// identify from: the fit gave every parameter exactly 0 with std 0, without a word. One passive joint (the
// pendubot's second) is fine; every joint without effort is not.
void require_some_effort(const io::CsvTable& table, const LogColumns& log) {
    if (table.rows() < 2) return;  // too short for anything: said elsewhere
    const auto all_zero = [](const std::vector<double>* c) { return std::all_of(c->begin(), c->end(), [](double v) { return v == 0.0; }); };
    if (!std::all_of(log.tau.begin(), log.tau.end(), all_zero)) return;
    std::string columns;
    for (const std::string& name : log.tau_names) columns += (columns.empty() ? "'" : ", '") + io::printable_cell(name) + "'";
    throw InputError(fmt::format("{}: every torque column ({}) is 0 in every one of its {} rows: no joint's effort was logged, so there is nothing "
                                 "to identify from (were the efforts null or not recorded?)",
                                 table.source(), columns, table.rows()));
}

}  // namespace

LogColumns log_columns(const io::CsvTable& table, const robot::RobotDescription& robot, const std::string& time_column,
                       double time_tolerance, double grid_period) {
    LogColumns log;
    log.source = table.source();
    if (grid_period > 0.0 && table.rows() < 2) {
        // A one-row segment of a split log: its period is the grid's (there is no step to check); too short
        // for any window, the pipeline reports it as unused.
        log.sample_period = grid_period;
        log.start_time = table.rows() == 1 ? table.column(time_column).front() : 0.0;
    } else {
        const io::TimeAxis axis = io::check_uniform_time(table, time_column, time_tolerance);
        log.sample_period = axis.sample_period;
        log.start_time = axis.start;
    }
    for (std::size_t j = 0; j < robot.joints.size(); ++j) {
        const std::string& column = robot.joints[j].position_column;
        log.q.push_back(&table.column(column));  // InputError names the file and the columns it has
        log.q_names.push_back(column);
        if (const auto bounds = position_bounds(robot, j)) {
            const std::vector<double>& q = *log.q.back();
            for (std::size_t r = 0; r < q.size(); ++r) {
                if (!bounds->holds(q[r])) {
                    throw InputError(fmt::format("{}:{}: column '{}': {}", table.source(), table.line_of_row(r), io::printable_cell(column), bounds->refusal(q[r])));
                }
            }
        }
    }
    for (const auto& j : robot.joints) {
        log.tau.push_back(&table.column(j.torque_column));
        log.tau_names.push_back(j.torque_column);
    }
    require_some_effort(table, log);
    for (std::size_t j = 1; j <= robot.joints.size(); ++j) {
        const std::string name = "qd" + std::to_string(j);  // as io::LogColumnNames and simulate --states name them
        log.qd.push_back(table.has_column(name) ? &table.column(name) : nullptr);
        // As simulate writes them (and --log-format's references: name them).
        const std::array<std::string, 2> references = reference_column_names(j - 1);
        log.q_ref.push_back(table.has_column(references[0]) ? &table.column(references[0]) : nullptr);
        log.qd_ref.push_back(table.has_column(references[1]) ? &table.column(references[1]) : nullptr);
    }
    return log;
}

std::vector<std::vector<double>*> writable_torques(io::CsvTable& table, const LogColumns& log) {
    std::vector<std::vector<double>*> columns;
    for (const std::string& name : log.tau_names) columns.push_back(&table.mutable_column(table.column_index(name)));
    return columns;
}

LogColumns log_columns(const std::vector<std::vector<double>>& q, const std::vector<std::vector<double>>& tau, double sample_period,
                       const std::string& source, double start_time) {
    if (q.empty() || q.size() != tau.size()) {
        throw InputError(fmt::format("{}: {} position and {} torque columns (one of each per joint, at least one joint)", source, q.size(), tau.size()));
    }
    if (!(sample_period > 0.0)) throw InputError(fmt::format("{}: sample period {} s must be > 0", source, sample_period));
    LogColumns log;
    log.source = source;
    log.sample_period = sample_period;
    log.start_time = start_time;
    for (std::size_t j = 0; j < q.size(); ++j) {
        if (q[j].size() != q.front().size() || tau[j].size() != q.front().size()) {
            throw InputError(fmt::format("{}: joint {} has {} positions and {} torques, joint 1 has {} samples", source, j + 1, q[j].size(),
                                         tau[j].size(), q.front().size()));
        }
        log.q.push_back(&q[j]);
        log.q_names.push_back(fmt::format("q{}", j + 1));
        log.tau.push_back(&tau[j]);
        log.tau_names.push_back(fmt::format("tau{}", j + 1));
    }
    return log;
}

}  // namespace jacobid::identify
