#pragma once
// A JSON document built in the order written (keys keep that order) and serialized by nlohmann::json
// (Debian nlohmann-json3-dev); the CLI prints it, Python turns tree() into a dict. Numbers round-trip; a
// whole double below 2^53 is written without a fraction ("120", as before); non-finite numbers and an
// empty std::optional are written as null (JSON has no NaN) so the output always parses; strings that
// are not valid UTF-8 get U+FFFD for the bad bytes.
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace mocapdb::json {

class JsonWriter {
public:
    JsonWriter();
    ~JsonWriter();
    JsonWriter(const JsonWriter&) = delete;
    JsonWriter& operator=(const JsonWriter&) = delete;

    JsonWriter& begin_object();
    JsonWriter& end_object();
    JsonWriter& begin_array();
    JsonWriter& end_array();
    JsonWriter& key(std::string_view name);
    JsonWriter& value(std::string_view text);
    JsonWriter& value(const char* text) { return value(std::string_view(text)); }
    JsonWriter& value(double number);
    JsonWriter& value(long long number);
    JsonWriter& value(std::size_t number) { return value(static_cast<long long>(number)); }
    JsonWriter& value(int number) { return value(static_cast<long long>(number)); }
    JsonWriter& value(bool flag);
    JsonWriter& value(const std::optional<double>& number) { return number ? value(*number) : null(); }
    JsonWriter& null();

    /// The document, compact, followed by a newline.
    std::string str() const;
    /// The document as a tree (ordered keys; non-finite numbers already null).
    const nlohmann::ordered_json& tree() const;

private:
    struct Document;  // the nlohmann tree and the path to the open container
    std::unique_ptr<Document> doc_;
};

}  // namespace mocapdb::json
