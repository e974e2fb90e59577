// SPDX-License-Identifier: MIT
#pragma once
// Keyword arguments parsed by the command line's own option definitions: bandwidth=5 is `--bandwidth 5`,
// log_format="ur10e.yaml" is `--log-format ur10e.yaml`, weighted=True is the flag `--weighted` (False: not
// given), a list or tuple is a comma-separated value (torque_noise=(0.05, 0.01)). The CLI's validators
// check the values, so a bad one raises jacobid.InputError with the message the command line prints.
#include <pybind11/pybind11.h>

#include <string>

namespace CLI {
class App;
}

namespace jacobid::python {

// Parses `keywords` into the options registered on `app` (named `command` in messages). InputError for an
// unknown keyword or a value the option refuses.
void parse_keywords(CLI::App& app, const pybind11::kwargs& keywords);

// A float as Python writes it (the shortest text that reads back to the same double).
std::string python_text(const pybind11::handle& value);

}  // namespace jacobid::python
