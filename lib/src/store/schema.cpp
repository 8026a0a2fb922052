#include "schema.hpp"

#include <cmath>

#include "layout.hpp"
#include "mocapdb/core/error.hpp"

namespace mocapdb::store {
namespace {

class Reader {
public:
    explicit Reader(const std::string& source) : source_(source) {}

    [[noreturn]] void fail(const std::string& where, const std::string& message) const {
        throw ParseError(source_, 0, 0, where + ": " + message);
    }

    const JsonValue& member(const JsonValue& object, const char* key, const std::string& where) const {
        const JsonValue* v = object.get(key);
        if (v == nullptr) fail(where, std::string("missing \"") + key + "\"");
        return *v;
    }

    std::string text(const JsonValue& object, const char* key, const std::string& where, bool required = true) const {
        const JsonValue* v = object.get(key);
        if (v == nullptr) {
            if (required) fail(where, std::string("missing \"") + key + "\"");
            return "";
        }
        if (v->type != JsonValue::Type::String) fail(where, std::string("\"") + key + "\" must be a string");
        return v->string;
    }

    std::vector<Extent> shape(const JsonValue& object, const std::string& where) const {
        std::vector<Extent> out;
        const JsonValue* v = object.get("shape");
        if (v == nullptr) return out;
        if (v->type != JsonValue::Type::Array) fail(where, "\"shape\" must be an array");
        for (const JsonValue& e : v->array) {
            Extent x;
            if (e.type == JsonValue::Type::String && !e.string.empty()) {
                x.symbol = e.string;
            } else if (e.type == JsonValue::Type::Number && e.number >= 0 && std::floor(e.number) == e.number) {
                x.value = static_cast<std::uint64_t>(e.number);
            } else {
                fail(where, "shape entries must be symbols or non-negative integers");
            }
            out.push_back(x);
        }
        return out;
    }

    ValueRules rules(const JsonValue& object, const std::string& where) const {
        ValueRules r;
        if (const JsonValue* v = object.get("value")) r.value = *v;
        if (const JsonValue* v = object.get("enum")) {
            if (v->type != JsonValue::Type::Array) fail(where, "\"enum\" must be an array");
            r.one_of = v->array;
        }
        auto number = [&](const char* key) -> std::optional<double> {
            const JsonValue* v = object.get(key);
            if (v == nullptr) return std::nullopt;
            if (v->type != JsonValue::Type::Number) fail(where, std::string("\"") + key + "\" must be a number");
            return v->number;
        };
        r.min = number("min");
        r.exclusive_min = number("exclusive_min");
        r.pattern = text(object, "pattern", where, false);
        if (!r.pattern.empty() && r.pattern != "hex64") fail(where, "unknown pattern \"" + r.pattern + "\"");
        r.ref = text(object, "ref", where, false);
        return r;
    }

    bool presence(const JsonValue& object, const std::string& where) const {
        const std::string p = text(object, "presence", where);
        if (p != "MUST" && p != "MAY") fail(where, "presence must be \"MUST\" or \"MAY\"");
        return p == "MUST";
    }

private:
    const std::string& source_;
};

}  // namespace

Schema parse_schema(std::string_view json, const std::string& source) {
    const JsonValue doc = parse_json(json, source);
    const Reader r(source);
    if (doc.type != JsonValue::Type::Object) r.fail("schema", "the document must be an object");
    Schema s;
    s.format = r.text(doc, "format", "schema");
    const JsonValue& version = r.member(doc, "format_version", "schema");
    if (version.type != JsonValue::Type::Number) r.fail("schema", "\"format_version\" must be a number");
    s.format_version = static_cast<std::int64_t>(version.number);
    s.user_attribute_prefix = r.text(doc, "user_attribute_prefix", "schema", false);
    const JsonValue& objects = r.member(doc, "objects", "schema");
    if (objects.type != JsonValue::Type::Array) r.fail("schema", "\"objects\" must be an array");
    for (const JsonValue& o : objects.array) {
        ObjectSpec spec;
        spec.path = r.text(o, "path", "object");
        const std::string where = "object " + spec.path;
        if (spec.path.empty() || spec.path.front() != '/') r.fail(where, "paths must be absolute");
        spec.segments = split_path(spec.path);
        const std::string type = r.text(o, "type", where);
        if (type != "group" && type != "dataset") r.fail(where, "type must be \"group\" or \"dataset\"");
        spec.group = type == "group";
        spec.required = r.presence(o, where);
        if (spec.required && !spec.segments.empty() && is_placeholder(spec.segments.back()))
            r.fail(where, "an object named by a placeholder cannot be MUST");
        if (spec.group) {
            spec.kind = r.text(o, "kind", where);
        } else {
            spec.dtype = r.text(o, "dtype", where);
            spec.units = r.text(o, "units", where);
            spec.shape = r.shape(o, where);
            const JsonValue& dims = r.member(o, "dims", where);
            if (dims.type != JsonValue::Type::Array) r.fail(where, "\"dims\" must be an array");
            for (const JsonValue& d : dims.array) {
                if (d.type != JsonValue::Type::String) r.fail(where, "dims must be strings");
                spec.dims.push_back(d.string);
            }
            if (spec.dims.size() != spec.shape.size()) r.fail(where, "dims and shape must have the same length");
            if (const JsonValue* f = o.get("filters")) {
                for (const JsonValue& x : f->array) spec.filters.push_back(x.string);
            }
            spec.rules = r.rules(o, where);
        }
        if (const JsonValue* attrs = o.get("attributes")) {
            for (const JsonValue& a : attrs->array) {
                AttributeSpec as;
                as.name = r.text(a, "name", where + " attribute");
                const std::string aw = where + " attribute " + as.name;
                as.dtype = r.text(a, "dtype", aw);
                as.shape = r.shape(a, aw);
                as.required = r.presence(a, aw);
                as.rules = r.rules(a, aw);
                spec.attributes.push_back(std::move(as));
            }
        }
        s.objects.push_back(std::move(spec));
    }
    return s;
}

}  // namespace mocapdb::store
