#pragma once
// The CLI's --json output as a small tree for assertions, parsed by nlohmann::json (strict RFC 8259:
// malformed input throws, so "it parses" is a real check).
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace mocapdb::test {

struct Json {
    enum Kind { Null, Bool, Number, String, Array, Object } kind = Null;
    bool boolean = false;
    double number = 0.0;
    std::string text;
    std::vector<Json> items;
    std::map<std::string, Json> members;

    const Json& operator[](const std::string& key) const {
        auto it = members.find(key);
        if (kind != Object || it == members.end()) throw std::runtime_error("json: no key " + key);
        return it->second;
    }
    const Json& operator[](std::size_t i) const {
        if (kind != Array || i >= items.size()) throw std::runtime_error("json: bad index");
        return items[i];
    }
    bool has(const std::string& key) const { return kind == Object && members.count(key) > 0; }

    static Json from(const nlohmann::json& j) {
        Json v;
        if (j.is_boolean()) {
            v.kind = Bool;
            v.boolean = j.get<bool>();
        } else if (j.is_number()) {
            v.kind = Number;
            v.number = j.get<double>();
        } else if (j.is_string()) {
            v.kind = String;
            v.text = j.get<std::string>();
        } else if (j.is_array()) {
            v.kind = Array;
            for (const auto& e : j) v.items.push_back(from(e));
        } else if (j.is_object()) {
            v.kind = Object;
            for (auto it = j.begin(); it != j.end(); ++it) v.members[it.key()] = from(it.value());
        }
        return v;
    }
};

/// Throws nlohmann::json::parse_error (a std::exception) on malformed JSON.
class JsonParser {
public:
    explicit JsonParser(std::string s) : s_(std::move(s)) {}
    Json parse() const { return Json::from(nlohmann::json::parse(s_)); }

private:
    std::string s_;
};

inline Json parse_json(const std::string& s) { return JsonParser(s).parse(); }

}  // namespace mocapdb::test
