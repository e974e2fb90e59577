// SPDX-License-Identifier: MIT
#pragma once
// The module's two areas, each adding its functions and classes to the extension module.
#include <pybind11/pybind11.h>

namespace jacobid::python {

// lib/: kernels, frequency response, batch differentiation, the streaming bank, the Butterworth + Euler baseline.
void bind_core(pybind11::module_& m);
// jacobid::host: robot descriptions, simulation, identification (+ validation), diagnosis.
void bind_host(pybind11::module_& m);
// jacobid payload (python/src/payload_bindings.cpp).
void bind_payload(pybind11::module_& m);
// Contact detection with the identified model: monitor, monitor_calibrate (monitor_bindings.cpp).
void bind_monitor(pybind11::module_& m);
// identify as a map-reduce: plan, factor, merge (fleet_bindings.cpp).
void bind_fleet(pybind11::module_& m);
// The runs of jacobid montecarlo one by one and their table, for jacobid.fleet.montecarlo (montecarlo_bindings.cpp).
void bind_montecarlo(pybind11::module_& m);

}  // namespace jacobid::python
