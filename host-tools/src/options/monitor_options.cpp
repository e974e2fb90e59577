// SPDX-License-Identifier: MIT
#include "options/monitor_options.hpp"

#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include "core/errors.hpp"
#include "options/option_checks.hpp"
#include "options/output_file.hpp"
#include "options/robot_files.hpp"
#include "monitor/calibration.hpp"
#include "monitor/contact_events.hpp"
#include "monitor/monitor_model.hpp"
#include "monitor/monitor_report.hpp"

namespace jacobid::options {
namespace {

std::vector<NamedPath> monitor_inputs(const MonitorInputs& o, const robot::RobotDescription& robot) {
    std::vector<NamedPath> inputs = robot_files("--robot", o.robot, robot);
    for (const auto& log : o.logs) inputs.push_back({"--in", log});
    inputs.push_back({"--log-format", o.log_format.file});
    return inputs;
}

monitor::MonitorLog read_monitor_log(const MonitorInputs& o, const std::string& path, const robot::RobotDescription& robot) {
    refuse_split(o.log_format, "monitor");
    const io::CsvTable table = read_log_table(path, o.log_format, robot_column_names(robot, o.time_column), true);
    return monitor::monitor_log(table, robot, o.time_column, o.time_tolerance);
}

void print_notes(const monitor::MonitorModel& model) {
    for (const auto& note : model.notes) fmt::print(stderr, "jacobid monitor: note: {}\n", note);
}

}  // namespace

void add_monitor_log_options(CLI::App* cmd, MonitorInputs& o) {
    cmd->add_option("--time-column", o.time_column, "name of the time column (seconds)")->capture_default_str();
    add_time_tolerance_option(cmd, o.time_tolerance);
    add_log_format_options(cmd, o.log_format);
}

void add_monitor_calibrate_options(CLI::App* cal, MonitorCalibrateOptions& c) {
    cal->add_option("--out,-o", c.out, "monitor file to write (YAML)")->check(file_path());
    cal->add_option("--false-alarm-rate", c.file.false_alarm_rate,
                    "per-sample false-alarm rate a: each threshold is the (1 - a) quantile of the contact-free estimates (the largest with fewer than 1/a samples)")
        ->check(number_in(0.0, 1.0))
        ->capture_default_str();
    cal->add_option("--margin", c.file.margin, "thresholds = (1 + margin) x quantile, for the logs not seen")->check(non_negative_number())->capture_default_str();
    cal->add_option("--estimator", c.estimator, "observer (generalized momentum, no acceleration) or residual (tau - model from the Jacobi bank)")
        ->check(CLI::IsMember({"observer", "residual"}))
        ->capture_default_str();
    cal->add_option("--gain", c.file.estimator.gain, "observer gain K (1/s): the estimate follows the external torque with time constant 1/K")
        ->check(positive_number())
        ->capture_default_str();
    cal->add_option("--velocity-window", c.file.estimator.velocity_window, "Jacobi window (s) of the position and velocity estimates")
        ->check(positive_number())
        ->capture_default_str();
    cal->add_option("--acceleration-window", c.file.estimator.acceleration_window, "Jacobi window (s) of the acceleration (residual estimator)")
        ->check(positive_number())
        ->capture_default_str();
    cal->add_option("--xi", c.file.estimator.xi, "kernel evaluation point: 0 central (delay half the window), towards 1 causal (shorter delay, more noise)")
        ->check(number_in(-1.0, 1.0))
        ->capture_default_str();
    cal->add_flag("--no-measured-velocity{false}", c.file.estimator.measured_velocity,
                  "differentiate the positions even when the log has measured velocities (qd1..)");
    cal->add_option("--standing-velocity", c.file.standing_velocity,
                    "rad/s below which a joint stands (its Coulomb band holds any torque inside it); one value or one per joint")
        ->delimiter(',')
        ->check(non_negative_number())
        ->capture_default_str();
    cal->add_option("--standing-time", c.file.standing_time, "s below the standing velocity before a joint stands (a reversal in mid-motion does not)")
        ->check(non_negative_number())
        ->capture_default_str();
    cal->add_option("--band-margin", c.file.band_margin,
                    "a standing joint's band is (1 + band margin) x its Coulomb level: it breaks away above its sliding friction; one value or one per joint")
        ->delimiter(',')
        ->check(non_negative_number())
        ->capture_default_str();
    cal->add_option("--confirm", c.file.confirm, "consecutive samples in contact before an event starts (1: at once; more rejects one-sample glitches)")
        ->check(whole_number_in(1, 1000))
        ->capture_default_str();
    cal->add_option("--hold", c.file.hold, "s: an event ends this long after its last sample in contact")->check(non_negative_number())->capture_default_str();
}

void add_monitor_replay_options(CLI::App* cmd, MonitorReplayOptions& m) {
    cmd->add_option("--plot", m.plot, "PNG of each joint's external torque, its threshold and the events")->check(file_path());
    cmd->add_option("--estimates", m.estimates, "CSV of the estimates: t, tau_ext1.., threshold1.. ('-': standard output)")->check(file_path(true));
}

MonitorRun run_monitor_calibrate(MonitorCalibrateOptions o) {
    if (o.robot.empty() || o.logs.empty() || o.out.empty()) throw InputError("monitor calibrate needs --robot, --in (one or more) and --out");
    if (!(o.file.false_alarm_rate >= 0.0 && o.file.false_alarm_rate < 1.0)) {
        throw InputError(fmt::format("--false-alarm-rate {} must be in [0, 1) (a fraction of samples)", o.file.false_alarm_rate));
    }
    o.file.estimator.estimator = o.estimator == "observer" ? monitor::Estimator::Observer : monitor::Estimator::Residual;
    const robot::RobotDescription robot = robot::load_robot_description(o.robot);
    check_outputs({{"--out", o.out}}, monitor_inputs(o, robot));
    std::vector<monitor::Replay> replays;
    for (const auto& path : o.logs) {
        const monitor::MonitorLog log = read_monitor_log(o, path, robot);
        // The standstill is counted in samples of this log's period.
        const monitor::MonitorModel model =
            monitor::load_monitor_model(o.robot, o.file.standing_velocity, o.file.standing_time, log.sample_period, o.file.band_margin);
        if (replays.empty()) print_notes(model);
        replays.push_back(monitor::replay(model, o.file.estimator, log));
        o.file.calibrated_from.push_back(path);
    }
    const auto joints = monitor::calibrate(replays, o.file.false_alarm_rate, o.file.margin);
    o.file.robot = o.robot;
    for (const auto& c : joints) o.file.thresholds.push_back(c.thresholds);
    write_output(o.out, monitor::to_yaml(o.file));
    return {monitor::calibration_json(joints, o.file), fmt::format("{}monitor file: {}\n", monitor::calibration_text(joints, o.file, robot), o.out)};
}

MonitorRun run_monitor_replay(const MonitorReplayOptions& o) {
    if (o.robot.empty() || o.monitor.empty() || o.logs.empty()) {
        throw InputError("monitor needs --robot, --monitor and --in (or the subcommand calibrate; see jacobid monitor --help)");
    }
    if (o.logs.size() != 1) throw InputError(fmt::format("--in: monitor replays one log, got {}", o.logs.size()));
    const robot::RobotDescription robot = robot::load_robot_description(o.robot);
    const monitor::MonitorFile file = monitor::load_monitor_file(o.monitor, robot.joints.size());
    std::vector<NamedPath> inputs = monitor_inputs(o, robot);
    inputs.push_back({"--monitor", o.monitor});
    check_outputs({{"--plot", o.plot}, {"--estimates", o.estimates}}, inputs);
    const monitor::MonitorLog log = read_monitor_log(o, o.logs.front(), robot);
    const monitor::MonitorModel model = monitor::load_monitor_model(o.robot, file.standing_velocity, file.standing_time, log.sample_period, file.band_margin);
    print_notes(model);
    const monitor::Replay replay = monitor::replay(model, file.estimator, log);
    const auto events = monitor::contact_events(replay, file.thresholds, file.hold, file.confirm);
    if (!o.estimates.empty()) write_output(o.estimates, monitor::estimates_csv(replay, file));
    if (!o.plot.empty()) monitor::plot_events(o.plot, events, replay, file, robot, o.logs.front());
    return {monitor::events_json(events, replay, file, robot, o.logs.front()), monitor::events_text(events, replay, robot)};
}

}  // namespace jacobid::options
