// SPDX-License-Identifier: MIT
// jacobid.payload(robot, arm, log, unloaded=None, **options): `jacobid payload --json` from Python (docs/python.md,
// docs/identify.md "Payload"): files in, the command's JSON out as a dict; the options are the command's
// (options/payload_options.hpp), parsed and checked by its own definitions, so the messages are the command line's.
#include <pybind11/pybind11.h>

#include <CLI/CLI.hpp>

#include "bindings.hpp"
#include "options/payload_options.hpp"
#include "cli_arguments.hpp"
#include "json_to_python.hpp"
#include "payload/payload_report.hpp"
#include "python_values.hpp"

namespace jacobid::python {
namespace {

namespace py = pybind11;

py::object payload(const py::object& robot, const py::object& arm, const py::object& log, const py::object& unloaded, const py::args& extra,
                   const py::kwargs& keywords) {
    refuse_extra_positional("payload", extra, {"robot", "arm", "log", "unloaded"});
    options::PayloadOptions o;
    o.quiet = true;  // a library call prints nothing; the command line's --quiet
    CLI::App app("", "payload");
    options::add_payload_options(&app, o);
    parse_keywords(app, keywords, {"robot", "arm", "log", "unloaded"});
    o.robot = path_text(robot, "robot");
    o.arm = path_text(arm, "arm");
    o.in = path_text(log, "log");
    if (!unloaded.is_none()) o.unloaded = path_text(unloaded, "unloaded");
    nlohmann::json result;
    {
        py::gil_scoped_release unlocked;
        result = payload::payload_json(options::run_payload(o).estimate);
    }
    return to_python(result);
}

}  // namespace

void bind_payload(py::module_& m) {
    const py::object none = py::none();
    m.def("_payload", &payload, py::arg("robot") = none, py::arg("arm") = none, py::arg("log") = none, py::arg("unloaded") = none);
}

}  // namespace jacobid::python
