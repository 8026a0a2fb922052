// The schema mirror's JSON, parsed by nlohmann::json (Debian nlohmann-json3-dev) into the JsonValue tree
// the schema code walks (objects keep their key order).
#include "json_value.hpp"

#include <cmath>

#include <nlohmann/json.hpp>

#include "mocapdb/core/error.hpp"

namespace mocapdb::store {
namespace {

using Ordered = nlohmann::ordered_json;

// The tree, at most 64 levels deep (the conversion recurses per level; nlohmann's parser does not).
JsonValue from_nlohmann(const Ordered& j, const std::string& source, int depth = 0) {
    if (depth > 64) throw ParseError(source, 0, 0, "nesting deeper than 64 levels");
    JsonValue v;
    switch (j.type()) {
        case Ordered::value_t::boolean:
            v.type = JsonValue::Type::Bool;
            v.boolean = j.get<bool>();
            break;
        case Ordered::value_t::number_integer:
        case Ordered::value_t::number_unsigned:
        case Ordered::value_t::number_float:
            v.type = JsonValue::Type::Number;
            v.number = j.get<double>();
            break;
        case Ordered::value_t::string:
            v.type = JsonValue::Type::String;
            v.string = j.get<std::string>();
            break;
        case Ordered::value_t::array:
            v.type = JsonValue::Type::Array;
            for (const auto& e : j) v.array.push_back(from_nlohmann(e, source, depth + 1));
            break;
        case Ordered::value_t::object:
            v.type = JsonValue::Type::Object;
            for (auto it = j.begin(); it != j.end(); ++it)
                v.object.emplace_back(it.key(), from_nlohmann(it.value(), source, depth + 1));
            break;
        default: break;  // null (and discarded / binary values, which the text cannot hold)
    }
    return v;
}

// 1-based line and column of byte offset `at` (nlohmann reports the offset just past the error).
std::pair<std::size_t, std::size_t> line_and_column(std::string_view text, std::size_t at) {
    std::size_t line = 1, col = 1;
    for (std::size_t k = 0; k < at && k < text.size(); ++k) {
        if (text[k] == '\n') {
            ++line;
            col = 1;
        } else {
            ++col;
        }
    }
    return {line, col};
}

}  // namespace

const JsonValue* JsonValue::get(std::string_view key) const {
    for (const auto& [k, v] : object)
        if (k == key) return &v;
    return nullptr;
}

std::string JsonValue::dump() const {
    // Scalars as nlohmann writes them (a whole number without a fraction, as the mirror writes it);
    // arrays and objects with ", " / ": " between their parts, for messages.
    switch (type) {
        case Type::Null: return "null";
        case Type::Bool: return boolean ? "true" : "false";
        case Type::Number:
            if (std::isfinite(number) && number == std::floor(number) && std::abs(number) < 9.0e15)
                return Ordered(static_cast<long long>(number)).dump();
            return Ordered(number).dump();
        case Type::String: return Ordered(string).dump(-1, ' ', false, Ordered::error_handler_t::replace);
        case Type::Array: {
            std::string out = "[";
            for (std::size_t k = 0; k < array.size(); ++k) out += (k ? ", " : "") + array[k].dump();
            return out + "]";
        }
        case Type::Object: {
            std::string out = "{";
            for (std::size_t k = 0; k < object.size(); ++k)
                out += (k ? ", " : "") +
                       Ordered(object[k].first).dump(-1, ' ', false, Ordered::error_handler_t::replace) + ": " +
                       object[k].second.dump();
            return out + "}";
        }
    }
    return "null";
}

JsonValue parse_json(std::string_view text, const std::string& source) {
    Ordered tree;
    try {
        tree = Ordered::parse(text.begin(), text.end());
    } catch (const Ordered::parse_error& e) {
        const auto [line, col] = line_and_column(text, e.byte > 0 ? e.byte - 1 : 0);
        // nlohmann's message starts "[json.exception.parse_error.101] parse error at line L, column C: ".
        std::string what = e.what();
        const auto colon = what.find(": ");
        throw ParseError(source, line, col, colon == std::string::npos ? what : what.substr(colon + 2));
    }
    return from_nlohmann(tree, source);
}

}  // namespace mocapdb::store
