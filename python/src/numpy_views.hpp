// SPDX-License-Identifier: MIT
#pragma once
// numpy arrays in and out. In: checked_array() is the one gate every array argument of the module passes
// before any computation: anything that is not an array of finite real numbers of the expected shape is an
// InputError naming the argument and, for a bad element, its index; what passes is a float64 C-contiguous
// array, the caller's own when it already is one (read in place, no copy), else converted once by numpy.
// Out: results computed into a std::vector are handed to numpy with the vector itself as the array's owner
// (a capsule), not copied.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <string>
#include <vector>

#include "jacobid/span.hpp"

namespace jacobid::python {

// A float64, C-contiguous array.
using DoubleArray = pybind11::array_t<double, pybind11::array::c_style | pybind11::array::forcecast>;

// Samples: one-dimensional. SamplesByJoints: two-dimensional, rows are samples (one-dimensional: one column).
enum class Layout { Samples, SamplesByJoints };

// `value` (an ndarray, a list or tuple, anything numpy reads as an array) as finite float64 numbers in
// `layout`, non-empty. Refused, naming `what`: None and non-arrays, ragged sequences, complex, bool, text and
// other non-number dtypes, elements that are not finite real numbers ("x[3] is nan", "q[5, 1] is None"),
// a single number, too many dimensions, no samples.
DoubleArray checked_array(const pybind11::handle& value, const std::string& what, Layout layout);

// The samples of a checked one-dimensional array.
Span<const double> samples_of(const DoubleArray& array);

// The rows x columns of a checked array (a one-dimensional one is one column).
struct Matrix {
    const double* data = nullptr;
    std::size_t rows = 0, columns = 0;
    double at(std::size_t row, std::size_t column) const { return data[row * columns + column]; }
};
Matrix matrix_of(const DoubleArray& array);

// A numpy array that owns `values` (moved, not copied).
pybind11::array_t<double> owning_array(std::vector<double>&& values);

// A new rows x columns float64 array (C order), to be written in place.
pybind11::array_t<double> new_matrix(std::size_t rows, std::size_t columns);

}  // namespace jacobid::python
