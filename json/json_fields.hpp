#pragma once
// Members the documents of json/ share (private to the target): a number or null, a list of strings,
// a vector of numbers. Each writes into the open JSON object or array of `j`.
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "mocapdb_json/json_writer.hpp"

namespace mocapdb::json::fields {

inline void optional_number(JsonWriter& j, const char* key, const std::optional<double>& v) {
    j.key(key);
    if (v) j.value(*v);
    else j.null();
}

inline void strings(JsonWriter& j, const char* key, const std::vector<std::string>& v) {
    j.key(key).begin_array();
    for (const std::string& s : v) j.value(s);
    j.end_array();
}

/// An array of the vector's values (no key: after key() or inside an array).
inline void numbers(JsonWriter& j, const Eigen::VectorXd& v) {
    j.begin_array();
    for (Eigen::Index k = 0; k < v.size(); ++k) j.value(v(k));
    j.end_array();
}

}  // namespace mocapdb::json::fields
