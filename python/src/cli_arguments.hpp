// SPDX-License-Identifier: MIT
#pragma once
// Keyword arguments parsed by the command line's own option definitions: bandwidth=5 is `--bandwidth 5`,
// log_format="ur10e.yaml" is `--log-format ur10e.yaml`, weighted=True is the flag `--weighted` (False: not
// given), a list, tuple or one-dimensional array is a comma-separated value (torque_noise=(0.05, 0.01)), None
// is not given. The CLI's validators check the values, so a bad one raises jacobid.InputError with the
// message the command line prints. Every keyword of every function of the module is checked here first: an
// unknown one is named as unknown with the closest valid keyword, never reported as some option missing.
#include <pybind11/pybind11.h>

#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace jacobid::python {

// InputError unless every keyword of `keywords` is one of `known` (the keywords of `function`), e.g.
// "windw: unknown keyword of differentiate (did you mean window?); its keywords: x, ts, window, ...".
void refuse_unknown_keywords(const std::string& function, const pybind11::dict& keywords, const std::vector<std::string>& known);

// InputError when `function`, which takes the positional arguments `positional`, was given more (`extra`, what
// py::args collected beyond them): pybind11 would answer "incompatible function arguments" and dump the call.
void refuse_extra_positional(const std::string& function, const pybind11::args& extra, const std::vector<std::string>& positional);

// Parses `keywords` into the options registered on `app`, named as the Python function (CLI::App("", "simulate")). `arguments`:
// the function's own arguments, which are keywords too (named in the list of keywords of an unknown one).
// InputError for an unknown keyword, a value of the wrong type (True for a value, 1 for a flag, a dict ...)
// or a value the option refuses.
void parse_keywords(CLI::App& app, const pybind11::dict& keywords, const std::vector<std::string>& arguments = {});

}  // namespace jacobid::python
