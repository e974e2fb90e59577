// SPDX-License-Identifier: MIT
#include "numpy_views.hpp"

#include <fmt/core.h>

#include "core/errors.hpp"

namespace py = pybind11;

namespace jacobid::python {

Span<const double> samples_of(const DoubleArray& array, const std::string& what) {
    if (array.ndim() != 1) throw InputError(fmt::format("{}: expected a one-dimensional array, got {} dimensions", what, array.ndim()));
    return Span<const double>(array.data(), static_cast<std::size_t>(array.shape(0)));
}

Matrix matrix_of(const DoubleArray& array, const std::string& what) {
    if (array.ndim() == 1) return {array.data(), static_cast<std::size_t>(array.shape(0)), 1};
    if (array.ndim() != 2) throw InputError(fmt::format("{}: expected an array of samples x joints, got {} dimensions", what, array.ndim()));
    return {array.data(), static_cast<std::size_t>(array.shape(0)), static_cast<std::size_t>(array.shape(1))};
}

py::array_t<double> owning_array(std::vector<double>&& values) {
    auto* owned = new std::vector<double>(std::move(values));
    py::capsule free_when_done(owned, [](void* p) { delete static_cast<std::vector<double>*>(p); });
    return py::array_t<double>({owned->size()}, {sizeof(double)}, owned->data(), free_when_done);
}

py::array_t<double> new_matrix(std::size_t rows, std::size_t columns) {
    return py::array_t<double>({rows, columns});
}

}  // namespace jacobid::python
