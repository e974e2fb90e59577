// SPDX-License-Identifier: MIT
#pragma once
// What one Python value is, for the module's checks and messages: paths given as str, bytes or os.PathLike,
// numbers of any kind (int, float, numpy scalars, but not bool or complex), and the name of the closest valid
// choice when a user misspells one. Every function of the module reads its paths and scalar values through
// here (numpy_views.hpp reads its arrays), so a value is judged the same way wherever it is given.
#include <pybind11/pybind11.h>

#include <string>
#include <vector>

namespace jacobid::python {

// "None", "int", "dict", ...: the type of `value` as Python names it.
std::string type_name(const pybind11::handle& value);

// Whether `value` is a path: str, bytes or os.PathLike.
bool is_path(const pybind11::handle& value);

// The file system path `value` names (os.fsencode: bytes and os.PathLike as the OS sees them, never "b'...'");
// InputError naming `what` for anything else.
std::string path_text(const pybind11::handle& value, const std::string& what);

// `text` as a Python str: UTF-8, any other byte kept as a surrogate escape, as os.fsdecode does, so that a
// path of raw bytes in a message or a result is shown (and os.fsencode gives the same bytes back) instead of
// the conversion failing.
pybind11::str text_of(const std::string& text);

// Whether `value` is True or False (Python's bool or numpy's).
bool is_bool(const pybind11::handle& value);

// Why `value` is not a finite real number ("None", "nan", "-inf", "str '3'", "complex (1+2j)", "bool True"),
// or "" when it is one.
std::string not_a_finite_number(const pybind11::handle& value);

// " (did you mean NAME?)" with the entry of `choices` closest to `name` (Python's difflib), or "" when none is close.
std::string did_you_mean(const std::string& name, const std::vector<std::string>& choices);

// "a, b, c".
std::string joined(const std::vector<std::string>& names);

}  // namespace jacobid::python
