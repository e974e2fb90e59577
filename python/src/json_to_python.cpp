// SPDX-License-Identifier: MIT
#include "json_to_python.hpp"

#include "python_values.hpp"

namespace py = pybind11;

namespace jacobid::python {

py::object to_python(const nlohmann::json& value) {
    switch (value.type()) {
        case nlohmann::json::value_t::null: return py::none();
        case nlohmann::json::value_t::boolean: return py::bool_(value.get<bool>());
        case nlohmann::json::value_t::number_integer: return py::int_(value.get<std::int64_t>());
        case nlohmann::json::value_t::number_unsigned: return py::int_(value.get<std::uint64_t>());
        case nlohmann::json::value_t::number_float: return py::float_(value.get<double>());
        case nlohmann::json::value_t::string: return text_of(value.get_ref<const std::string&>());  // a path may be any bytes
        case nlohmann::json::value_t::array: {
            py::list list;
            for (const auto& item : value) list.append(to_python(item));
            return std::move(list);
        }
        case nlohmann::json::value_t::object: {
            py::dict dict;
            for (const auto& [key, item] : value.items()) dict[py::str(key)] = to_python(item);
            return std::move(dict);
        }
        case nlohmann::json::value_t::binary:
        case nlohmann::json::value_t::discarded: break;
    }
    return py::none();
}

}  // namespace jacobid::python
