// SPDX-License-Identifier: MIT
#include "cli_arguments.hpp"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <vector>

#include "core/errors.hpp"

namespace py = pybind11;

namespace jacobid::python {

std::string python_text(const py::handle& value) {
    if (py::isinstance<py::str>(value)) return value.cast<std::string>();
    // repr of a float round-trips (17 significant digits where needed); str(numpy.float64) does too.
    if (py::isinstance<py::float_>(value)) return py::repr(value).cast<std::string>();
    return py::str(value).cast<std::string>();
}

void parse_keywords(CLI::App& app, const py::kwargs& keywords) {
    std::vector<std::string> args;
    for (const auto& [key, value] : keywords) {
        std::string name = key.cast<std::string>();
        std::replace(name.begin(), name.end(), '_', '-');
        const std::string option = "--" + name;
        if (value.is_none()) continue;  // None: not given, the option's default
        if (py::isinstance<py::bool_>(value)) {
            if (value.cast<bool>()) args.push_back(option);
            continue;
        }
        std::string text;
        if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
            for (const auto& item : value) text += (text.empty() ? "" : ",") + python_text(item);
        } else {
            text = python_text(value);
        }
        args.push_back(option);
        args.push_back(text);
    }
    std::reverse(args.begin(), args.end());  // CLI::App::parse(vector) takes the arguments last first
    try {
        app.parse(args);
    } catch (const CLI::ParseError& e) {
        throw InputError(e.what());
    }
}

}  // namespace jacobid::python
