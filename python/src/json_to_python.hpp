// SPDX-License-Identifier: MIT
#pragma once
// nlohmann::json -> plain Python objects (dict, list, str, int, float, bool, None), so that the module's
// results carry exactly the names and values of the command line's JSON output (the same producers).
#include <pybind11/pybind11.h>

#include <nlohmann/json.hpp>

namespace jacobid::python {

pybind11::object to_python(const nlohmann::json& value);

}  // namespace jacobid::python
