// SPDX-License-Identifier: MIT
#include "options/log_format_options.hpp"

#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include <unordered_map>

#include "options/option_checks.hpp"
#include "core/errors.hpp"
#include "identify/plan/log_columns.hpp"

namespace jacobid::options {

void add_log_format_options(CLI::App* command, LogFormatOptions& o) {
    command->add_option("--log-format", o.file,
                        "YAML description of a raw log (header, delimiter, skip_rows, time, positions, velocities, torques or currents "
                        "with gains; docs/log-format.md): --in and --validate are read with it and resampled onto a uniform grid");
    command->add_flag("--skip-bad-rows", o.read.skip_bad_rows,
                      "with --log-format: skip malformed rows and rows whose time does not increase, reporting each (default: error)");
    command->add_option("--on-gap", o.on_gap,
                        "with --log-format: a time step longer than --max-gap is an error, is interpolated, or splits the log into "
                        "segments processed separately (identify, differentiate; docs/log-format.md)")
        ->check(CLI::IsMember({"error", "interpolate", "split"}))
        ->capture_default_str();
    command->add_option("--max-gap", o.read.max_gap, "with --log-format: longest time step in s that is not a gap (default: 3 median steps)")
        ->check(positive_number());
    command->add_option("--interpolate-max", o.read.interpolate_max, "with --on-gap interpolate: most missing samples a gap may span")
        ->check(whole_number_from(0))
        ->capture_default_str();
}

void add_time_tolerance_option(CLI::App* command, double& tolerance) {
    command->add_option("--time-tolerance", tolerance, "allowed deviation of each time step from the sample period, as a fraction")
        ->check(number_in(0.0, 1.0))
        ->capture_default_str();
}

void refuse_split(const LogFormatOptions& o, const std::string& command) {
    if (o.on_gap == "split") throw InputError(fmt::format("--on-gap split is not supported by {}; use interpolate", command));
}

io::CsvTable read_log_table(const std::string& path, const LogFormatOptions& o, io::LogColumnNames names, bool quiet, double period) {
    if (o.on_gap == "split") throw InputError("--on-gap split is not supported by this command (it reads one continuous log); use interpolate");
    return std::move(read_log_segments(path, o, std::move(names), quiet, period).tables.front());
}

LogSegments read_log_segments(const std::string& path, const LogFormatOptions& o, io::LogColumnNames names, bool quiet, double period,
                              const io::CsvColumnFilter& keep) {
    LogSegments out;
    out.split = o.on_gap == "split";
    if (o.file.empty()) {
        if (o.read.skip_bad_rows || o.on_gap != "error" || o.read.max_gap > 0.0) {
            throw InputError("--skip-bad-rows, --on-gap and --max-gap apply to logs read with --log-format");
        }
        out.tables.push_back(io::read_csv(path, {}, keep));
        return out;
    }
    const io::LogFormat format = io::load_log_format(o.file);
    if (names.q.empty()) {
        names = io::LogColumnNames::numbered(format.joints(), names.time);
    } else if (names.q.size() != format.joints()) {
        throw InputError(fmt::format("--log-format {}: {} positions, but the robot description has {} joints", o.file, format.joints(), names.q.size()));
    }
    io::LogReadSettings settings = o.read;
    settings.period = period;
    settings.on_gap = o.on_gap == "interpolate" ? io::GapPolicy::Interpolate : out.split ? io::GapPolicy::Split : io::GapPolicy::Error;
    io::LogReadReport report;
    out.tables = io::read_formatted_log_segments(path, format, names, settings, report);
    out.segments = report.segments;
    out.grid_period = report.grid_period;
    // Skipped rows and the summary are always printed (never silently absorbed); the per-step lines only
    // without --quiet.
    for (const auto& s : report.skipped) fmt::print(stderr, "{} (skipped)\n", s);
    if (!quiet) {
        for (std::size_t i = 0; i < report.irregular_lines.size(); ++i) {
            fmt::print(stderr, "{}:{}: irregular time step {:.4g} ms (median {:.4g} ms)\n", path, report.irregular_lines[i],
                       1e3 * report.irregular_steps[i], 1e3 * report.median_step);
        }
        for (std::size_t i = 0; i < report.gap_lines.size(); ++i) {
            fmt::print(stderr, "{}:{}: gap of {:.4g} ms {}\n", path, report.gap_lines[i], 1e3 * report.gap_steps[i],
                       out.split ? "(the log is split there)" : "interpolated");
        }
        if (out.split) {
            for (std::size_t s = 0; s < report.segments.size(); ++s) {
                fmt::print(stderr, "{}: segment {}: {}\n", path, s + 1, report.segments[s].describe());
            }
        }
    }
    fmt::print(stderr, "{}\n", report.summary());
    return out;
}

io::LogColumnNames robot_column_names(const robot::RobotDescription& robot, const std::string& time_column) {
    io::LogColumnNames names;
    names.time = time_column;
    // Each signal reads its own column: two joints on one column (or a joint on the time column) would
    // identify from a copied or a time signal without a word.
    std::unordered_map<std::string, std::string> user_of{{time_column, "the time column (--time-column)"}};
    const auto claim = [&](const std::string& column, const std::string& user) {
        const auto [it, fresh] = user_of.emplace(column, user);
        if (!fresh) {
            throw InputError(fmt::format("{}: {} reads column '{}', which is also {}; give each signal its own column", robot.source, user,
                                         column, it->second));
        }
    };
    for (std::size_t j = 0; j < robot.joints.size(); ++j) {
        const std::string joint = fmt::format("joint {} ({})", j + 1, robot.joints[j].name);
        claim(robot.joints[j].position_column, joint + "'s position");
        claim(robot.joints[j].torque_column, joint + "'s torque");
        names.q.push_back(robot.joints[j].position_column);
        names.qd.push_back(fmt::format("qd{}", j + 1));
        names.tau.push_back(robot.joints[j].torque_column);
        names.q_bounds.push_back(identify::position_bounds(robot, j));
    }
    return names;
}

}  // namespace jacobid::options
