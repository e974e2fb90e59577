// SPDX-License-Identifier: MIT
#include "options/payload_options.hpp"

#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include <optional>

#include "core/errors.hpp"
#include "options/option_checks.hpp"
#include "identify/plan/log_columns.hpp"
#include "io/distinct_inputs.hpp"
#include "payload/payload_export.hpp"
#include "robot/urdf_chain.hpp"

namespace jacobid::options {
namespace {

// The output frame in the last link's frame: --tool-frame x,y,z,roll,pitch,yaw (URDF's convention, R = Rz Ry
// Rx), or --frame LINK: the last link itself, or (URDF robot) a link fixed to it, e.g. the flange tool0.
Eigen::Isometry3d tool_pose(const PayloadOptions& o, const robot::RobotDescription& robot, std::string& name) {
    Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
    if (!o.frame.empty() && !o.tool_frame.empty()) throw InputError("--frame and --tool-frame: give one of them");
    const std::string last = payload::last_link_name(robot);
    name = last + " (the last link's frame)";
    if (!o.tool_frame.empty()) {
        const auto& v = o.tool_frame;
        t.translation() = Eigen::Vector3d(v[0], v[1], v[2]);
        t.linear() = (Eigen::AngleAxisd(v[5], Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(v[4], Eigen::Vector3d::UnitY()) *
                      Eigen::AngleAxisd(v[3], Eigen::Vector3d::UnitX()))
                         .toRotationMatrix();
        name = fmt::format("tool frame xyz ({}, {}, {}) rpy ({}, {}, {}) in {}", v[0], v[1], v[2], v[3], v[4], v[5], last);
        return t;
    }
    if (o.frame.empty() || o.frame == last) return t;
    if (robot.model != "urdf") throw InputError(fmt::format("--frame {}: expected {} (link names other than the last need a URDF robot; or give --tool-frame)", o.frame, last));
    const robot::UrdfChain chain = robot::load_urdf_chain(robot.urdf);
    const int body = static_cast<int>(chain.joints.size()) - 1;
    for (const robot::UrdfLinkFrame& link : chain.links) {
        if (link.name != o.frame) continue;
        if (link.body != body) {
            throw InputError(fmt::format("--frame {}: the link is not fixed to the last link {} of {} (a payload is carried by the last link)", o.frame, last, robot.urdf));
        }
        t.linear() = link.rotation;
        t.translation() = link.position;
        name = fmt::format("{} (fixed to {})", o.frame, last);
        return t;
    }
    throw InputError(fmt::format("--frame {}: no such link in {} (expected {} or a link fixed to it)", o.frame, robot.urdf, last));
}

}  // namespace

void add_payload_options(CLI::App* cmd, PayloadOptions& o) {
    cmd->add_option("--frame", o.frame, "the output frame: the last link (default) or, for a URDF robot, a link fixed to it (e.g. tool0)");
    cmd->add_option("--tool-frame", o.tool_frame, "the output frame x,y,z,roll,pitch,yaw (m, rad; URDF rpy) in the last link's frame")
        ->delimiter(',')
        ->expected(6)
        ->check(finite_number());
    o.mass_option = cmd->add_option("--mass", o.mass, "the payload's mass if known (kg, > 0): then only the centre of mass and the inertia")
                         ->check(positive_number());
    cmd->add_option("--gain-std", o.gain_std,
                    "relative std of each joint's drive gain (e.g. 0.02 for 2 %, one per joint) to include in the payload's std")
        ->delimiter(',')
        ->check(non_negative_number());
    cmd->add_option("--time-column", o.time_column, "name of the time column (s)")->capture_default_str();
    add_time_tolerance_option(cmd, o.time_tolerance);
    add_log_format_options(cmd, o.log_format);
    add_fit_options(cmd, o.fit);
}

PayloadRun run_payload(const PayloadOptions& o) {
    PayloadRun run{robot::load_robot_description(o.robot), {}, {}};
    const robot::RobotDescription& robot = run.robot;
    refuse_split(o.log_format, "payload");
    if (!o.unloaded.empty()) io::require_distinct_inputs("--in/--unloaded", {o.in, o.unloaded});

    payload::PayloadSettings settings;
    settings.identify = identify_settings(o.fit, identify::Method::Jacobi);
    if (identify::is_iterated(settings.identify.estimator.estimator)) throw InputError("payload with --estimator iv|didim: use wls or ols");
    if (o.mass_option && o.mass_option->count() > 0) settings.mass = o.mass;
    settings.gain_std = o.gain_std;
    settings.tool = tool_pose(o, robot, settings.frame_name);

    run.arm = payload::load_arm(o.arm, robot);
    const io::LogColumnNames names = robot_column_names(robot, o.time_column);
    const io::CsvTable loaded_table = read_log_table(o.in, o.log_format, names, o.quiet);
    const identify::LogColumns loaded = identify::log_columns(loaded_table, robot, o.time_column, o.time_tolerance);
    std::optional<io::CsvTable> unloaded_table;
    std::optional<identify::LogColumns> unloaded;
    if (!o.unloaded.empty()) {
        try {
            unloaded_table.emplace(read_log_table(o.unloaded, o.log_format, names, o.quiet));
        } catch (const InputError& e) {
            throw InputError(fmt::format("--unloaded {}", e.what()));
        }
        unloaded = identify::log_columns(*unloaded_table, robot, o.time_column, o.time_tolerance);
    }
    run.estimate = payload::estimate_payload(run.arm, loaded, unloaded ? &*unloaded : nullptr, settings);
    return run;
}

}  // namespace jacobid::options
