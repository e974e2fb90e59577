// SPDX-License-Identifier: MIT
#include "identify/log_columns.hpp"

#include "io/time_axis.hpp"

namespace jacobid::identify {

LogColumns log_columns(const io::CsvTable& table, const robot::RobotDescription& robot, const std::string& time_column,
                       double time_tolerance) {
    LogColumns log;
    log.source = table.source();
    const io::TimeAxis axis = io::check_uniform_time(table, time_column, time_tolerance);
    log.sample_period = axis.sample_period;
    log.start_time = axis.start;
    for (const auto& j : robot.joints) {
        log.q.push_back(&table.column(j.position_column));  // InputError names the file and the columns it has
        log.q_names.push_back(j.position_column);
    }
    for (const auto& j : robot.joints) {
        log.tau.push_back(&table.column(j.torque_column));
        log.tau_names.push_back(j.torque_column);
    }
    for (std::size_t j = 1; j <= robot.joints.size(); ++j) {
        const std::string name = "qd" + std::to_string(j);  // as io::LogColumnNames and simulate --states name them
        log.qd.push_back(table.has_column(name) ? &table.column(name) : nullptr);
    }
    return log;
}

}  // namespace jacobid::identify
