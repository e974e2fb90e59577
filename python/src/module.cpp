// SPDX-License-Identifier: MIT
// jacobid._jacobid, the compiled part of the Python package `jacobid` (python/jacobid/__init__.py re-exports it).
#include <pybind11/pybind11.h>

#include <new>
#include <string>

#include "bindings.hpp"
#include "core/errors.hpp"
#include "python_values.hpp"

PYBIND11_MODULE(_jacobid, m) {
    m.doc() = "jacobid: robot dynamic identification with the Jacobi differentiator (compiled part; use `import jacobid`)";
    m.attr("__version__") = JACOBID_VERSION;
    // Any other C++ exception is a bug, not bad input: "internal error: ..." as the command line says it (exit 3
    // there), a RuntimeError here, never the IndexError or ValueError pybind11 would make of std::out_of_range or
    // std::invalid_argument. Registered first, so tried last: pybind11's own exceptions and InputError pass.
    pybind11::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const pybind11::builtin_exception&) {
            throw;
        } catch (const pybind11::error_already_set&) {
            throw;
        } catch (const std::bad_alloc&) {
            throw;
        } catch (const jacobid::InputError&) {
            throw;
        } catch (const std::exception& e) {
            PyErr_SetObject(PyExc_RuntimeError, jacobid::python::text_of(std::string("internal error: ") + e.what()).ptr());
        }
    });
    // Bad input: the command line's one-line message (naming the file, line, column, option), as a ValueError.
    // The message may name a path of any bytes: decoded as os.fsdecode does (pybind11's own translator gave an
    // empty message for a path that is not UTF-8).
    static pybind11::exception<jacobid::InputError> input_error(m, "InputError", PyExc_ValueError);
    pybind11::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const jacobid::InputError& e) {
            PyErr_SetObject(input_error.ptr(), jacobid::python::text_of(e.what()).ptr());
        }
    });
    jacobid::python::bind_core(m);
    jacobid::python::bind_host(m);
    jacobid::python::bind_payload(m);
    jacobid::python::bind_monitor(m);
    jacobid::python::bind_fleet(m);
    jacobid::python::bind_montecarlo(m);
}
