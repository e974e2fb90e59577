// SPDX-License-Identifier: MIT
// jacobid.monitor and jacobid.monitor_calibrate: contact detection with the identified model, as `jacobid
// monitor --json` and `jacobid monitor calibrate --json` (docs/monitor.md). The options are the command line's
// (cli/monitor_options.hpp), parsed from the keywords by the module's one layer (cli_arguments.hpp), so bad
// input raises InputError with the command line's message.
#include <CLI/CLI.hpp>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "cli/monitor_options.hpp"
#include "cli_arguments.hpp"
#include "core/errors.hpp"
#include "json_to_python.hpp"
#include "python_values.hpp"

namespace jacobid::python {
namespace {

namespace py = pybind11;

// A path, or a list or tuple of paths (calibrate's logs).
std::vector<std::string> paths_of(const py::handle& value, const std::string& what) {
    if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
        std::vector<std::string> paths;
        for (const py::handle item : value) paths.push_back(path_text(item, what));
        if (paths.empty()) throw InputError(what + ": expected one or more paths, got an empty list");
        return paths;
    }
    return {path_text(value, what)};
}

py::object monitor(const py::object& robot, const py::object& log, const py::object& monitor_file, const py::args& extra, const py::kwargs& keywords) {
    refuse_extra_positional("monitor", extra, {"robot", "log", "monitor"});
    cli::MonitorReplayOptions o;
    CLI::App app("", "monitor");
    cli::add_monitor_log_options(&app, o);
    cli::add_monitor_replay_options(&app, o);
    parse_keywords(app, keywords, {"robot", "log", "monitor"});
    o.robot = path_text(robot, "robot");
    o.logs = {path_text(log, "log")};
    o.monitor = path_text(monitor_file, "monitor");
    nlohmann::json j;
    {
        py::gil_scoped_release unlocked;
        j = cli::run_monitor_replay(o).json;
    }
    return to_python(j);
}

py::object monitor_calibrate(const py::object& robot, const py::object& logs, const py::object& out, const py::args& extra, const py::kwargs& keywords) {
    refuse_extra_positional("monitor_calibrate", extra, {"robot", "logs", "out"});
    cli::MonitorCalibrateOptions o;
    CLI::App app("", "monitor_calibrate");
    cli::add_monitor_log_options(&app, o);
    cli::add_monitor_calibrate_options(&app, o);
    parse_keywords(app, keywords, {"robot", "logs", "out"});
    o.robot = path_text(robot, "robot");
    o.logs = paths_of(logs, "logs");
    o.out = path_text(out, "out");
    nlohmann::json j;
    {
        py::gil_scoped_release unlocked;
        j = cli::run_monitor_calibrate(o).json;
    }
    return to_python(j);
}

}  // namespace

void bind_monitor(py::module_& m) {
    const py::object none = py::none();
    m.def("monitor", &monitor, py::arg("robot") = none, py::arg("log") = none, py::arg("monitor") = none,
          "monitor(robot, log, monitor, *, plot=..., estimates=..., log_format=..., time_column=...) -> dict\n\n"
          "Replays `log` through the identified model's external-torque estimator with the thresholds of the `monitor` file, as "
          "`jacobid monitor --json` (docs/monitor.md): events (start, end, joints, peak, peak_time, median), thresholds, delay.");
    m.def("monitor_calibrate", &monitor_calibrate, py::arg("robot") = none, py::arg("logs") = none, py::arg("out") = none,
          "monitor_calibrate(robot, logs, out, *, false_alarm_rate=1e-4, margin=0.25, estimator='observer', gain=100, ...) -> dict\n\n"
          "Per-joint thresholds from contact-free `logs` (a path or a list of paths), written to `out`, as `jacobid monitor "
          "calibrate --json`.");
}

}  // namespace jacobid::python
