#include "json_value.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdio>

#include "mocapdb/core/error.hpp"

namespace mocapdb::store {
namespace {

class Parser {
public:
    Parser(std::string_view text, const std::string& source) : t_(text), source_(source) {}

    JsonValue document() {
        JsonValue v = value(0);
        skip();
        if (i_ != t_.size()) fail("unexpected text after the JSON value");
        return v;
    }

private:
    std::string_view t_;
    const std::string& source_;
    std::size_t i_ = 0;

    [[noreturn]] void fail(const std::string& message) const {
        std::size_t line = 1, col = 1;
        for (std::size_t k = 0; k < i_ && k < t_.size(); ++k) {
            if (t_[k] == '\n') {
                ++line;
                col = 1;
            } else {
                ++col;
            }
        }
        throw ParseError(source_, line, col, message);
    }

    void skip() {
        while (i_ < t_.size() && (t_[i_] == ' ' || t_[i_] == '\t' || t_[i_] == '\n' || t_[i_] == '\r')) ++i_;
    }

    void expect(char c) {
        skip();
        if (i_ >= t_.size() || t_[i_] != c) fail(std::string("expected '") + c + "'");
        ++i_;
    }

    bool literal(std::string_view word) {
        if (t_.substr(i_, word.size()) != word) return false;
        i_ += word.size();
        return true;
    }

    JsonValue value(int depth) {
        if (depth > 64) fail("nesting deeper than 64 levels");
        skip();
        if (i_ >= t_.size()) fail("unexpected end of text (expected a value)");
        JsonValue v;
        const char c = t_[i_];
        if (c == '{') {
            ++i_;
            v.type = JsonValue::Type::Object;
            skip();
            if (i_ < t_.size() && t_[i_] == '}') {
                ++i_;
                return v;
            }
            for (;;) {
                skip();
                if (i_ >= t_.size() || t_[i_] != '"') fail("expected a quoted member name");
                std::string key = string_literal();
                expect(':');
                v.object.emplace_back(std::move(key), value(depth + 1));
                skip();
                if (i_ < t_.size() && t_[i_] == ',') {
                    ++i_;
                    continue;
                }
                expect('}');
                return v;
            }
        }
        if (c == '[') {
            ++i_;
            v.type = JsonValue::Type::Array;
            skip();
            if (i_ < t_.size() && t_[i_] == ']') {
                ++i_;
                return v;
            }
            for (;;) {
                v.array.push_back(value(depth + 1));
                skip();
                if (i_ < t_.size() && t_[i_] == ',') {
                    ++i_;
                    continue;
                }
                expect(']');
                return v;
            }
        }
        if (c == '"') {
            v.type = JsonValue::Type::String;
            v.string = string_literal();
            return v;
        }
        if (literal("true")) {
            v.type = JsonValue::Type::Bool;
            v.boolean = true;
            return v;
        }
        if (literal("false")) {
            v.type = JsonValue::Type::Bool;
            return v;
        }
        if (literal("null")) return v;
        std::size_t end = i_;
        while (end < t_.size() && (std::isdigit(static_cast<unsigned char>(t_[end])) || t_[end] == '-' ||
                                   t_[end] == '+' || t_[end] == '.' || t_[end] == 'e' || t_[end] == 'E'))
            ++end;
        const auto [ptr, ec] = std::from_chars(t_.data() + i_, t_.data() + end, v.number);
        if (end == i_ || ec != std::errc() || ptr != t_.data() + end) fail("expected a value");
        v.type = JsonValue::Type::Number;
        i_ = end;
        return v;
    }

    std::string string_literal() {
        ++i_;  // opening quote
        std::string out;
        for (;;) {
            if (i_ >= t_.size()) fail("unterminated string");
            const char c = t_[i_++];
            if (c == '"') return out;
            if (static_cast<unsigned char>(c) < 0x20) fail("control character in a string");
            if (c != '\\') {
                out += c;
                continue;
            }
            if (i_ >= t_.size()) fail("unterminated escape");
            const char e = t_[i_++];
            switch (e) {
                case '"': out += '"'; break;
                case '\\': out += '\\'; break;
                case '/': out += '/'; break;
                case 'b': out += '\b'; break;
                case 'f': out += '\f'; break;
                case 'n': out += '\n'; break;
                case 'r': out += '\r'; break;
                case 't': out += '\t'; break;
                case 'u': {
                    unsigned code = 0;
                    const auto [ptr, ec] = std::from_chars(t_.data() + i_, t_.data() + std::min(i_ + 4, t_.size()), code, 16);
                    if (ec != std::errc() || ptr != t_.data() + i_ + 4) fail("expected four hex digits after \\u");
                    i_ += 4;
                    if (code < 0x80) {
                        out += static_cast<char>(code);
                    } else if (code < 0x800) {
                        out += static_cast<char>(0xC0 | (code >> 6));
                        out += static_cast<char>(0x80 | (code & 0x3F));
                    } else {
                        out += static_cast<char>(0xE0 | (code >> 12));
                        out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
                        out += static_cast<char>(0x80 | (code & 0x3F));
                    }
                    break;
                }
                default: fail(std::string("unknown escape \\") + e);
            }
        }
    }
};

}  // namespace

const JsonValue* JsonValue::get(std::string_view key) const {
    for (const auto& [k, v] : object)
        if (k == key) return &v;
    return nullptr;
}

std::string JsonValue::dump() const {
    switch (type) {
        case Type::Null: return "null";
        case Type::Bool: return boolean ? "true" : "false";
        case Type::Number: {
            char buffer[32];
            const auto r = std::to_chars(buffer, buffer + sizeof buffer, number);
            return std::string(buffer, r.ptr);
        }
        case Type::String: return "\"" + string + "\"";
        case Type::Array: {
            std::string out = "[";
            for (std::size_t k = 0; k < array.size(); ++k) out += (k ? ", " : "") + array[k].dump();
            return out + "]";
        }
        case Type::Object: {
            std::string out = "{";
            for (std::size_t k = 0; k < object.size(); ++k)
                out += (k ? ", \"" : "\"") + object[k].first + "\": " + object[k].second.dump();
            return out + "}";
        }
    }
    return "null";
}

JsonValue parse_json(std::string_view text, const std::string& source) { return Parser(text, source).document(); }

}  // namespace mocapdb::store
