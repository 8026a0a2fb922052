#pragma once
// The schema mirror as a JSON tree (objects keep their key order); parsed by nlohmann::json.
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace mocapdb::store {

struct JsonValue {
    enum class Type { Null, Bool, Number, String, Array, Object };
    Type type = Type::Null;
    bool boolean = false;
    double number = 0.0;
    std::string string;
    std::vector<JsonValue> array;
    std::vector<std::pair<std::string, JsonValue>> object;

    /// The member `key` of an object; nullptr when absent or not an object.
    const JsonValue* get(std::string_view key) const;
    /// Compact JSON text of the value (for messages).
    std::string dump() const;
};

/// Parses JSON text (RFC 8259, by nlohmann::json; at most 64 levels of nesting). ParseError with line and
/// column on malformed input; `source` names the text.
JsonValue parse_json(std::string_view text, const std::string& source);

}  // namespace mocapdb::store
