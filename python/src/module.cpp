// SPDX-License-Identifier: MIT
// jacobid._jacobid, the compiled part of the Python package `jacobid` (python/jacobid/__init__.py re-exports it).
#include <pybind11/pybind11.h>

#include "bindings.hpp"
#include "core/errors.hpp"

PYBIND11_MODULE(_jacobid, m) {
    m.doc() = "jacobid: robot dynamic identification with the Jacobi differentiator (compiled part; use `import jacobid`)";
    m.attr("__version__") = JACOBID_VERSION;
    // Bad input: the command line's one-line message (naming the file, line, column, option), as a ValueError.
    pybind11::register_exception<jacobid::InputError>(m, "InputError", PyExc_ValueError);
    jacobid::python::bind_core(m);
    jacobid::python::bind_host(m);
}
