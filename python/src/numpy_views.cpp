// SPDX-License-Identifier: MIT
#include "numpy_views.hpp"

#include <fmt/core.h>

#include <cmath>

#include "core/errors.hpp"
#include "python_values.hpp"

namespace py = pybind11;

namespace jacobid::python {
namespace {

// "[7]" or "[5, 1]": the index of flat element `k` in an array of `shape`, as numpy writes it.
std::string index_text(std::size_t k, const std::vector<std::size_t>& shape) {
    std::vector<std::size_t> index(shape.size());
    for (std::size_t d = shape.size(); d-- > 0;) {
        index[d] = k % shape[d];
        k /= shape[d];
    }
    std::string s;
    for (const std::size_t i : index) s += (s.empty() ? "" : ", ") + std::to_string(i);
    return "[" + s + "]";
}

std::vector<std::size_t> shape_of(const py::array& a) {
    std::vector<std::size_t> shape;
    for (py::ssize_t d = 0; d < a.ndim(); ++d) shape.push_back(static_cast<std::size_t>(a.shape(d)));
    return shape;
}

// The array numpy makes of `value`. A list or tuple mixing numbers with None or text is taken element by
// element (dtype object), so that the element is named as the user wrote it, not as numpy converted it
// (np.asarray([1.0, "3"]) is text throughout, [1.0, None] becomes NaN once cast to float).
py::array as_numpy_array(const py::handle& value, const std::string& what) {
    if (py::isinstance<py::array>(value)) return py::reinterpret_borrow<py::array>(value);
    const bool sequence = py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value);
    if (!sequence && !py::hasattr(value, "__array__") && !py::hasattr(value, "__array_interface__")) {
        if (py::isinstance(value, py::module_::import("numbers").attr("Number")) && !is_bool(value)) {
            return py::reinterpret_borrow<py::array>(py::module_::import("numpy").attr("asarray")(value));  // 0-d, named below
        }
        throw InputError(fmt::format("{}: expected an array of numbers, got {}", what, type_name(value)));
    }
    const py::object asarray = py::module_::import("numpy").attr("asarray");
    try {
        py::array a = asarray(value);
        const char kind = a.dtype().kind();
        if (sequence && (kind == 'O' || kind == 'U' || kind == 'S')) a = asarray(value, "object");
        return a;
    } catch (const py::error_already_set& e) {
        if (!e.matches(PyExc_ValueError)) throw;
        throw InputError(fmt::format("{}: a nested sequence whose rows differ in length; expected an array of numbers", what));
    }
}

}  // namespace

DoubleArray checked_array(const py::handle& value, const std::string& what, Layout layout) {
    const std::string expected = layout == Layout::Samples ? "a one-dimensional array of samples" : "an array of samples x joints";
    py::array a = as_numpy_array(value, what);
    const std::string dtype = py::str(a.dtype()).cast<std::string>();
    switch (a.dtype().kind()) {
        case 'f':
        case 'i':
        case 'u': break;
        case 'c':
            throw InputError(fmt::format("{}: complex numbers (dtype {}); expected real numbers (pass x.real if the imaginary part is to be dropped)",
                                         what, dtype));
        case 'b': throw InputError(fmt::format("{}: booleans (dtype {}); expected numbers", what, dtype));
        case 'U':
        case 'S': throw InputError(fmt::format("{}: text (dtype {}); expected numbers", what, dtype));
        case 'O': {
            if (a.ndim() == 0) throw InputError(fmt::format("{}: expected an array of numbers, got {}", what, type_name(a.attr("item")())));
            std::size_t k = 0;
            for (const py::handle element : a.attr("flat")) {
                const std::string why = not_a_finite_number(element);
                if (!why.empty()) throw InputError(fmt::format("{}{} is {}; expected a finite number", what, index_text(k, shape_of(a)), why));
                ++k;
            }
            a = a.attr("astype")("float64").cast<py::array>();
            break;
        }
        default: throw InputError(fmt::format("{}: expected numbers, got dtype {}", what, dtype));
    }
    const std::vector<std::size_t> shape = shape_of(a);
    const std::string shape_text = py::str(a.attr("shape")).cast<std::string>();
    if (a.ndim() == 0) throw InputError(fmt::format("{}: a single number; expected {}", what, expected));
    if (a.ndim() > (layout == Layout::Samples ? 1 : 2)) throw InputError(fmt::format("{}: an array of shape {}; expected {}", what, shape_text, expected));
    if (a.size() == 0) throw InputError(fmt::format("{}: empty (shape {}); expected at least one sample", what, shape_text));
    DoubleArray checked = DoubleArray::ensure(a);
    if (!checked) throw py::error_already_set();
    const double* data = checked.data();
    for (std::size_t k = 0; k < static_cast<std::size_t>(checked.size()); ++k) {
        if (!std::isfinite(data[k])) throw InputError(fmt::format("{}{} is {}; expected a finite number", what, index_text(k, shape), data[k]));
    }
    return checked;
}

Span<const double> samples_of(const DoubleArray& array) { return Span<const double>(array.data(), static_cast<std::size_t>(array.shape(0))); }

Matrix matrix_of(const DoubleArray& array) {
    const auto rows = static_cast<std::size_t>(array.shape(0));
    return {array.data(), rows, array.ndim() == 1 ? 1 : static_cast<std::size_t>(array.shape(1))};
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
