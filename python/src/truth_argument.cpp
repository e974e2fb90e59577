// SPDX-License-Identifier: MIT
#include "truth_argument.hpp"

#include <fmt/core.h>

#include <algorithm>

#include "core/errors.hpp"
#include "io/csv_table.hpp"
#include "python_values.hpp"

namespace py = pybind11;

namespace jacobid::python {
namespace {

// The "parameters" of simulate --truth's JSON file (read by the CLI's input reader, which refuses devices and
// oversized files; parsed by Python's json), checked as a dict from here on.
py::object parameters_of_file(const std::string& path) {
    const std::string text = io::read_text_file(path, "--truth file");
    py::object j;
    try {
        j = py::module_::import("json").attr("loads")(py::bytes(text));
    } catch (const py::error_already_set& e) {
        if (!e.matches(PyExc_ValueError)) throw;
        throw InputError(fmt::format("truth {}: invalid JSON: {}", path, py::str(e.value()).cast<std::string>()));
    }
    if (!py::isinstance<py::dict>(j) || !j.contains("parameters")) throw InputError(fmt::format("truth {}: no object 'parameters'", path));
    return j["parameters"];
}

}  // namespace

std::map<std::string, double> truth_values(const py::handle& value, const std::vector<std::string>& parameters) {
    py::object given;
    if (is_path(value)) {
        given = parameters_of_file(path_text(value, "truth"));
    } else if (py::isinstance<py::dict>(value)) {
        const py::dict d = py::reinterpret_borrow<py::dict>(value);
        given = d.contains("parameters") ? py::object(d["parameters"]) : py::reinterpret_borrow<py::object>(value);  // simulate()'s result
    }
    if (!given || !py::isinstance<py::dict>(given)) {
        throw InputError(fmt::format("truth: expected a dict name -> value, simulate()'s result or the path of simulate --truth's JSON file, got {}",
                                     type_name(given ? given : value)));
    }
    std::map<std::string, double> truth;
    for (const auto& [key, number] : py::reinterpret_borrow<py::dict>(given)) {
        const std::string name = py::str(key).cast<std::string>();
        if (!py::isinstance<py::str>(key) || std::find(parameters.begin(), parameters.end(), name) == parameters.end()) {
            throw InputError(fmt::format("truth: parameter {} is not one of the robot's{}; its parameters: {}", py::repr(key).cast<std::string>(),
                                         did_you_mean(name, parameters), joined(parameters)));
        }
        const std::string why = not_a_finite_number(number);
        if (!why.empty()) throw InputError(fmt::format("truth['{}'] is {}; expected a finite number", name, why));
        truth[name] = py::float_(py::reinterpret_borrow<py::object>(number)).cast<double>();
    }
    for (const std::string& name : parameters) {
        if (truth.count(name) == 0) {
            throw InputError(fmt::format("truth: no parameter '{}', which the robot has ({} given, {} in the model): the truth of another robot or "
                                         "parameter set?",
                                         name, truth.size(), parameters.size()));
        }
    }
    return truth;
}

}  // namespace jacobid::python
