// SPDX-License-Identifier: MIT
#include "cli_arguments.hpp"

#include <CLI/CLI.hpp>
#include <fmt/core.h>
#include <pybind11/numpy.h>

#include <algorithm>
#include <vector>

#include "core/errors.hpp"
#include "python_values.hpp"

namespace py = pybind11;

namespace jacobid::python {
namespace {

// One value as the command line's text: a number as Python writes it (the shortest text that reads back to the
// same double), text as is, a path as the OS sees it. InputError naming `option` for any other type.
std::string value_text(const py::handle& value, const std::string& option) {
    if (py::isinstance<py::str>(value)) return value.cast<std::string>();
    if (py::isinstance<py::array>(value) && py::reinterpret_borrow<py::array>(value).ndim() == 0) return value_text(value.attr("item")(), option);
    if (is_path(value)) return path_text(value, option);
    const py::module_ numbers = py::module_::import("numbers");
    if (is_bool(value)) throw InputError(fmt::format("{}: expected a value, got {}", option, py::repr(value).cast<std::string>()));
    if (py::isinstance(value, numbers.attr("Integral"))) return py::str(py::int_(py::reinterpret_borrow<py::object>(value))).cast<std::string>();
    if (py::isinstance(value, numbers.attr("Real"))) return py::repr(py::float_(py::reinterpret_borrow<py::object>(value))).cast<std::string>();
    if (py::isinstance(value, numbers.attr("Complex"))) {
        throw InputError(fmt::format("{}: expected a real number, got {} {}", option, type_name(value), py::repr(value).cast<std::string>()));
    }
    throw InputError(fmt::format("{}: expected a number, text or path, got {}", option, type_name(value)));
}

bool is_list(const py::handle& value) {
    return py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value) ||
           (py::isinstance<py::array>(value) && py::reinterpret_borrow<py::array>(value).ndim() == 1);
}

std::string keyword_of(std::string option_name) {
    std::replace(option_name.begin(), option_name.end(), '-', '_');
    return option_name;
}

}  // namespace

void refuse_unknown_keywords(const std::string& function, const py::dict& keywords, const std::vector<std::string>& known) {
    for (const auto& [key, value] : keywords) {
        const std::string name = key.cast<std::string>();
        if (std::find(known.begin(), known.end(), name) == known.end()) {
            const std::string keywords_text = known.empty() ? "it takes none" : "its keywords: " + joined(known);
            throw InputError(fmt::format("{}: unknown keyword of {}{}; {}", name, function, did_you_mean(name, known), keywords_text));
        }
    }
}

void refuse_extra_positional(const std::string& function, const py::args& extra, const std::vector<std::string>& positional) {
    if (extra.empty()) return;
    const std::size_t given = positional.size() + extra.size();
    throw InputError(fmt::format("{}: got {} positional argument{}, takes {}{}; give the options as keywords", function, given, given == 1 ? "" : "s",
                                 positional.size(), positional.empty() ? std::string() : " (" + joined(positional) + ")"));
}

void parse_keywords(CLI::App& app, const py::dict& keywords, const std::vector<std::string>& arguments) {
    // No help option: CLI11 answers --help with an exception whose text is "This should be caught in your main
    // function", and help= is no keyword of the module anyway.
    app.set_help_flag();
    std::vector<std::string> known = arguments;
    for (const CLI::Option* option : app.get_options()) {
        for (const std::string& name : option->get_lnames()) known.push_back(keyword_of(name));
    }
    refuse_unknown_keywords(app.get_name(), keywords, known);
    std::vector<std::string> args;
    for (const auto& [key, value] : keywords) {
        std::string name = key.cast<std::string>();
        if (std::find(arguments.begin(), arguments.end(), name) != arguments.end()) continue;  // the function's own
        std::replace(name.begin(), name.end(), '_', '-');
        const std::string option = "--" + name;
        if (value.is_none()) continue;  // None: not given, the option's default
        if (app.get_option(option)->get_expected_max() == 0) {  // a flag: True gives it, False does not
            if (!is_bool(value)) throw InputError(fmt::format("{}: a flag, expected True or False, got {}", option, py::repr(value).cast<std::string>()));
            if (value.cast<bool>()) args.push_back(option);
            continue;
        }
        std::string text;
        if (is_list(value)) {
            for (const auto& item : value) text += (text.empty() ? "" : ",") + value_text(item, option);
        } else {
            text = value_text(value, option);
        }
        // Nothing: CLI11 would take the next argument as the value (None is how an option is left out).
        if (text.empty()) throw InputError(fmt::format("{}: expected a value, got {}", option, py::repr(value).cast<std::string>()));
        // --name=value: a value that starts with "-" (a negative number, a text like "--ts") is the value, never an option.
        args.push_back(option + "=" + text);
    }
    std::reverse(args.begin(), args.end());  // CLI::App::parse(vector) takes the arguments last first
    try {
        app.parse(args);
    } catch (const CLI::ParseError& e) {
        throw InputError(e.what());
    }
}

}  // namespace jacobid::python
