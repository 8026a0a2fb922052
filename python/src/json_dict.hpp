#pragma once
// A step's JSON document (json/mocapdb_json/*_json.hpp) as Python objects: objects become dicts (keys in
// document order), arrays lists, null None; so a workflow function returns the keys of `--json`.
#include <pybind11/pybind11.h>

#include <nlohmann/json.hpp>

namespace mocapdb::python {

inline pybind11::object to_python(const nlohmann::ordered_json& v) {
    namespace py = pybind11;
    switch (v.type()) {
        case nlohmann::ordered_json::value_t::object: {
            py::dict d;
            for (const auto& [key, item] : v.items()) d[py::str(key)] = to_python(item);
            return std::move(d);
        }
        case nlohmann::ordered_json::value_t::array: {
            py::list l;
            for (const auto& item : v) l.append(to_python(item));
            return std::move(l);
        }
        case nlohmann::ordered_json::value_t::string: return py::str(v.get_ref<const std::string&>());
        case nlohmann::ordered_json::value_t::boolean: return py::bool_(v.get<bool>());
        case nlohmann::ordered_json::value_t::number_integer: return py::int_(v.get<long long>());
        case nlohmann::ordered_json::value_t::number_unsigned: return py::int_(v.get<unsigned long long>());
        case nlohmann::ordered_json::value_t::number_float: return py::float_(v.get<double>());
        default: return py::none();
    }
}

}  // namespace mocapdb::python
