// SPDX-License-Identifier: MIT
// jacobid monitor: contact detection with the identified model (docs/monitor.md).
//   jacobid monitor calibrate --robot identified.yaml --in a.csv --in b.csv ... --out monitor.yaml
//       per-joint thresholds (moving, standing) from contact-free logs at a stated false-alarm rate;
//   jacobid monitor --robot identified.yaml --monitor monitor.yaml --in log.csv [--json] [--plot events.png]
//       replays a log through the controller's estimator and reports the contact events.
// Options and runs: cli/monitor_options.hpp (shared with the Python module).
#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include <memory>

#include "cli/command.hpp"
#include "options/monitor_options.hpp"
#include "options/option_checks.hpp"

namespace jacobid::cli {
namespace {

void add_robot_and_logs(CLI::App* cmd, MonitorInputs& o, bool several, bool& json) {
    cmd->add_option("--robot", o.robot, "robot description (YAML) with the identified parameters, e.g. from identify --export-robot")->check(file_path());
    cmd->add_option("--in,-i", o.logs, several ? "contact-free log (CSV; repeatable)" : "log to replay (CSV)")->check(file_path());
    add_monitor_log_options(cmd, o);
    cmd->add_flag("--json", json, "JSON on standard output instead of the table");
}

void print(const MonitorRun& run, bool json) { fmt::print("{}", json ? run.json.dump(2) + "\n" : run.text); }

}  // namespace

void add_monitor_command(CLI::App& app) {
    auto m = std::make_shared<MonitorReplayOptions>();
    auto m_json = std::make_shared<bool>(false);
    CLI::App* cmd = app.add_subcommand("monitor",
                                       "contact detection with the identified model: replay a log through the controller's external-torque estimator and "
                                       "report the contact events (start, end, joints, peak external torque); thresholds from `monitor calibrate`");
    add_robot_and_logs(cmd, *m, false, *m_json);
    cmd->add_option("--monitor", m->monitor, "monitor file (YAML) written by jacobid monitor calibrate")->check(file_path());
    add_monitor_replay_options(cmd, *m);
    cmd->require_subcommand(0, 1);

    auto c = std::make_shared<MonitorCalibrateOptions>();
    auto c_json = std::make_shared<bool>(false);
    CLI::App* cal = cmd->add_subcommand("calibrate", "per-joint thresholds (moving and standing) from contact-free logs at a stated false-alarm rate");
    add_robot_and_logs(cal, *c, true, *c_json);
    add_monitor_calibrate_options(cal, *c);
    cal->get_option("--robot")->required();
    cal->get_option("--in")->required();
    cal->get_option("--out")->required();
    cal->callback([c, c_json] { print(run_monitor_calibrate(*c), *c_json); });
    cmd->callback([m, m_json, cmd, cal] {
        if (cmd->got_subcommand(cal)) return;
        print(run_monitor_replay(*m), *m_json);
    });
}

}  // namespace jacobid::cli
