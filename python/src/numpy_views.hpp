// SPDX-License-Identifier: MIT
#pragma once
// numpy arrays in and out without copies where the layout allows: inputs are read in place when they are
// C-contiguous float64 (anything else is converted once, by numpy, as forcecast says), and results computed into
// a std::vector are handed to numpy with the vector itself as the array's owner (a capsule), not copied.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <string>
#include <vector>

#include "jacobid/span.hpp"

namespace jacobid::python {

// A float64, C-contiguous array: a view of the caller's array when it already is one.
using DoubleArray = pybind11::array_t<double, pybind11::array::c_style | pybind11::array::forcecast>;

// The samples of a one-dimensional array; InputError naming `what` for another shape.
Span<const double> samples_of(const DoubleArray& array, const std::string& what);

// The rows x columns of a two-dimensional array (a one-dimensional one is one column); InputError naming `what`.
struct Matrix {
    const double* data = nullptr;
    std::size_t rows = 0, columns = 0;
    double at(std::size_t row, std::size_t column) const { return data[row * columns + column]; }
};
Matrix matrix_of(const DoubleArray& array, const std::string& what);

// A numpy array that owns `values` (moved, not copied).
pybind11::array_t<double> owning_array(std::vector<double>&& values);

// A new rows x columns float64 array (C order), to be written in place.
pybind11::array_t<double> new_matrix(std::size_t rows, std::size_t columns);

}  // namespace jacobid::python
