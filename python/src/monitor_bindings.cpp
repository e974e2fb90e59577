// SPDX-License-Identifier: MIT
// jacobid.monitor and jacobid.monitor_calibrate: contact detection with the identified model, as `jacobid
// monitor --json` and `jacobid monitor calibrate --json` (docs/monitor.md). The options are the command line's
// (options/monitor_options.hpp), parsed from the keywords by the module's one layer (cli_arguments.hpp), so bad
// input raises InputError with the command line's message.
#include <CLI/CLI.hpp>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "options/monitor_options.hpp"
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

// Both functions: the arguments checked, the keywords parsed by the command's options (`add` registers the
// function's own beside the log options), `fill` sets the arguments, `run` computes without the GIL.
template <typename Options, typename Add, typename Fill, typename Run>
py::object run_monitor_function(const std::string& name, const std::vector<std::string>& arguments, const py::args& extra,
                                const py::kwargs& keywords, Add add, Fill fill, Run run) {
    refuse_extra_positional(name, extra, arguments);
    Options o;
    CLI::App app("", name);
    options::add_monitor_log_options(&app, o);
    add(&app, o);
    parse_keywords(app, keywords, arguments);
    fill(o);
    nlohmann::json j;
    {
        py::gil_scoped_release unlocked;
        j = run(o).json;
    }
    return to_python(j);
}

py::object monitor(const py::object& robot, const py::object& log, const py::object& monitor_file, const py::args& extra, const py::kwargs& keywords) {
    return run_monitor_function<options::MonitorReplayOptions>(
        "monitor", {"robot", "log", "monitor"}, extra, keywords, options::add_monitor_replay_options,
        [&](options::MonitorReplayOptions& o) {
            o.robot = path_text(robot, "robot");
            o.logs = {path_text(log, "log")};
            o.monitor = path_text(monitor_file, "monitor");
        },
        options::run_monitor_replay);
}

py::object monitor_calibrate(const py::object& robot, const py::object& logs, const py::object& out, const py::args& extra, const py::kwargs& keywords) {
    return run_monitor_function<options::MonitorCalibrateOptions>(
        "monitor_calibrate", {"robot", "logs", "out"}, extra, keywords, options::add_monitor_calibrate_options,
        [&](options::MonitorCalibrateOptions& o) {
            o.robot = path_text(robot, "robot");
            o.logs = paths_of(logs, "logs");
            o.out = path_text(out, "out");
        },
        options::run_monitor_calibrate);
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
