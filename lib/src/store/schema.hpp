#pragma once
// The schema mirror (schemas/format-v1.json) as data the validator walks.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "json_value.hpp"

namespace mocapdb::store {

/// One axis of a shape: an exact extent, or a symbol bound per placeholder values.
struct Extent {
    std::string symbol;       ///< empty for an exact extent
    std::uint64_t value = 0;  ///< the exact extent
};

/// Constraints on values (an attribute's, or every element of a dataset).
struct ValueRules {
    std::optional<JsonValue> value;       ///< must equal
    std::vector<JsonValue> one_of;        ///< "enum"
    std::optional<double> min;            ///< >=
    std::optional<double> exclusive_min;  ///< >
    std::string pattern;                  ///< "hex64"
    std::string ref;                      ///< "/clips/{}": each value names an existing object
    bool any() const { return value || !one_of.empty() || min || exclusive_min || !pattern.empty() || !ref.empty(); }
};

struct AttributeSpec {
    std::string name;
    std::string dtype;
    std::vector<Extent> shape;
    bool required = false;
    ValueRules rules;
};

struct ObjectSpec {
    std::string path;                   ///< pattern, e.g. "/clips/{clip}/channels"
    std::vector<std::string> segments;  ///< "clips", "{clip}", "channels"
    bool group = false;
    std::string kind;  ///< groups
    bool required = false;
    std::string dtype;  ///< datasets
    std::vector<std::string> dims;
    std::vector<Extent> shape;
    std::string units;
    std::vector<std::string> filters;
    std::vector<AttributeSpec> attributes;
    ValueRules rules;  ///< on every element of a dataset
};

struct Schema {
    std::string format;
    std::int64_t format_version = 0;
    std::string user_attribute_prefix;
    std::vector<ObjectSpec> objects;
};

/// ParseError (for bad JSON or a malformed schema) naming `source`.
Schema parse_schema(std::string_view json, const std::string& source);

/// True when the segment is a placeholder "{name}".
inline bool is_placeholder(const std::string& segment) {
    return segment.size() >= 2 && segment.front() == '{' && segment.back() == '}';
}

}  // namespace mocapdb::store
