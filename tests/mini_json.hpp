#pragma once
// A small strict JSON parser for checking the CLI's --json output in tests (objects, arrays, strings,
// numbers, true/false/null). Throws std::runtime_error on malformed input, so "it parses" is a real check.
#include <cctype>
#include <cstdlib>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

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
};

class JsonParser {
public:
    explicit JsonParser(std::string s) : s_(std::move(s)) {}
    Json parse() {
        Json v = value();
        ws();
        if (p_ != s_.size()) fail("trailing characters");
        return v;
    }

private:
    [[noreturn]] void fail(const std::string& what) {
        throw std::runtime_error("json: " + what + " at offset " + std::to_string(p_));
    }
    void ws() {
        while (p_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[p_]))) ++p_;
    }
    bool eat(char c) {
        ws();
        if (p_ < s_.size() && s_[p_] == c) {
            ++p_;
            return true;
        }
        return false;
    }
    void expect(char c) {
        if (!eat(c)) fail(std::string("expected ") + c);
    }
    std::string str() {
        expect('"');
        std::string out;
        while (p_ < s_.size() && s_[p_] != '"') {
            if (s_[p_] == '\\') {
                ++p_;
                if (p_ >= s_.size()) fail("bad escape");
                const char e = s_[p_];
                if (e == 'u') {
                    if (p_ + 4 >= s_.size()) fail("bad unicode escape");
                    out.push_back('?');
                    p_ += 4;
                } else {
                    out.push_back(e == 'n' ? '\n' : e == 't' ? '\t' : e == 'r' ? '\r' : e);
                }
            } else {
                out.push_back(s_[p_]);
            }
            ++p_;
        }
        if (p_ >= s_.size()) fail("unterminated string");
        ++p_;
        return out;
    }
    Json value() {
        ws();
        if (p_ >= s_.size()) fail("unexpected end");
        Json v;
        const char c = s_[p_];
        if (c == '{') {
            ++p_;
            v.kind = Json::Object;
            if (eat('}')) return v;
            do {
                ws();
                const std::string k = str();
                expect(':');
                v.members[k] = value();
            } while (eat(','));
            expect('}');
        } else if (c == '[') {
            ++p_;
            v.kind = Json::Array;
            if (eat(']')) return v;
            do {
                v.items.push_back(value());
            } while (eat(','));
            expect(']');
        } else if (c == '"') {
            v.kind = Json::String;
            v.text = str();
        } else if (s_.compare(p_, 4, "true") == 0) {
            v.kind = Json::Bool;
            v.boolean = true;
            p_ += 4;
        } else if (s_.compare(p_, 5, "false") == 0) {
            v.kind = Json::Bool;
            p_ += 5;
        } else if (s_.compare(p_, 4, "null") == 0) {
            p_ += 4;
        } else {
            const char* begin = s_.c_str() + p_;
            char* end = nullptr;
            v.number = std::strtod(begin, &end);
            if (end == begin) fail("expected a value");
            v.kind = Json::Number;
            p_ += static_cast<std::size_t>(end - begin);
        }
        return v;
    }
    std::string s_;
    std::size_t p_ = 0;
};

inline Json parse_json(const std::string& s) { return JsonParser(s).parse(); }

}  // namespace mocapdb::test
