// SPDX-License-Identifier: MIT
#include "python_values.hpp"

#include <fmt/core.h>
#include <pybind11/stl.h>

#include <cmath>

#include "core/errors.hpp"

namespace py = pybind11;

namespace jacobid::python {

std::string type_name(const py::handle& value) {
    if (value.is_none()) return "None";
    return py::type::handle_of(value).attr("__name__").cast<std::string>();
}

bool is_path(const py::handle& value) {
    return py::isinstance<py::str>(value) || py::isinstance<py::bytes>(value) || py::hasattr(value, "__fspath__");
}

std::string path_text(const py::handle& value, const std::string& what) {
    if (!is_path(value)) throw InputError(fmt::format("{}: expected a path (str, bytes or os.PathLike), got {}", what, type_name(value)));
    try {
        // The bytes the OS gets: a str that is not UTF-8 on disk (surrogate escapes) stays the same file.
        return py::module_::import("os").attr("fsencode")(value).cast<std::string>();
    } catch (const py::error_already_set& e) {
        // An os.PathLike whose __fspath__ returns neither str nor bytes.
        throw InputError(fmt::format("{}: expected a path (str, bytes or os.PathLike), got {} ({})", what, type_name(value), e.what()));
    }
}

py::str text_of(const std::string& text) {
    PyObject* s = PyUnicode_DecodeUTF8(text.data(), static_cast<Py_ssize_t>(text.size()), "surrogateescape");
    if (s == nullptr) throw py::error_already_set();
    return py::reinterpret_steal<py::str>(s);
}

bool is_bool(const py::handle& value) {
    return py::isinstance<py::bool_>(value) || py::isinstance(value, py::module_::import("numpy").attr("bool_"));
}

std::string not_a_finite_number(const py::handle& value) {
    if (value.is_none()) return "None";
    const py::module_ numbers = py::module_::import("numbers");
    if (is_bool(value)) return fmt::format("bool {}", py::repr(value).cast<std::string>());
    if (py::isinstance(value, numbers.attr("Real"))) {
        const double x = py::float_(py::reinterpret_borrow<py::object>(value)).cast<double>();
        return std::isfinite(x) ? std::string() : fmt::format("{}", x);
    }
    // complex, str, list, ...: the type and the value as Python shows it.
    return fmt::format("{} {}", type_name(value), py::repr(value).cast<std::string>());
}

std::string did_you_mean(const std::string& name, const std::vector<std::string>& choices) {
    const py::list close = py::module_::import("difflib").attr("get_close_matches")(name, choices, 1);
    return close.empty() ? std::string() : fmt::format(" (did you mean {}?)", close[0].cast<std::string>());
}

std::string joined(const std::vector<std::string>& names) {
    std::string s;
    for (const auto& name : names) s += (s.empty() ? "" : ", ") + name;
    return s;
}

}  // namespace jacobid::python
