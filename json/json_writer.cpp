#include "mocapdb_json/json_writer.hpp"

#include <cmath>
#include <stdexcept>
#include <vector>

#include <nlohmann/json.hpp>

namespace mocapdb::json {

struct JsonWriter::Document {
    nlohmann::ordered_json root;
    std::vector<nlohmann::ordered_json*> open;  // containers begun and not yet ended, innermost last
    std::string pending_key;
    bool has_key = false;
    bool started = false;

    // Places v in the innermost open container (under the pending key in an object), or as the root.
    nlohmann::ordered_json& put(nlohmann::ordered_json v) {
        if (open.empty()) {
            if (started) throw std::logic_error("JsonWriter: a second top-level value");
            started = true;
            root = std::move(v);
            return root;
        }
        nlohmann::ordered_json& parent = *open.back();
        if (parent.is_object()) {
            if (!has_key) throw std::logic_error("JsonWriter: an object member without a key");
            has_key = false;
            parent[pending_key] = std::move(v);
            return parent[pending_key];
        }
        parent.push_back(std::move(v));
        return parent.back();
    }
};

JsonWriter::JsonWriter() : doc_(std::make_unique<Document>()) {}
JsonWriter::~JsonWriter() = default;

JsonWriter& JsonWriter::begin_object() {
    doc_->open.push_back(&doc_->put(nlohmann::ordered_json::object()));
    return *this;
}

JsonWriter& JsonWriter::end_object() {
    doc_->open.pop_back();
    return *this;
}

JsonWriter& JsonWriter::begin_array() {
    doc_->open.push_back(&doc_->put(nlohmann::ordered_json::array()));
    return *this;
}

JsonWriter& JsonWriter::end_array() {
    doc_->open.pop_back();
    return *this;
}

JsonWriter& JsonWriter::key(std::string_view name) {
    doc_->pending_key = std::string(name);
    doc_->has_key = true;
    return *this;
}

JsonWriter& JsonWriter::value(std::string_view text) {
    doc_->put(std::string(text));
    return *this;
}

JsonWriter& JsonWriter::value(double number) {
    if (!std::isfinite(number)) return null();
    // A whole number keeps the form it had before nlohmann ("120", not "120.0"); -0 stays a double.
    if (number == std::floor(number) && std::abs(number) < 9007199254740992.0 &&
        !(number == 0.0 && std::signbit(number)))
        doc_->put(static_cast<long long>(number));
    else doc_->put(number);
    return *this;
}

JsonWriter& JsonWriter::value(long long number) {
    doc_->put(number);
    return *this;
}

JsonWriter& JsonWriter::value(bool flag) {
    doc_->put(flag);
    return *this;
}

JsonWriter& JsonWriter::null() {
    doc_->put(nullptr);
    return *this;
}

const nlohmann::ordered_json& JsonWriter::tree() const { return doc_->root; }

std::string JsonWriter::str() const {
    return doc_->root.dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace) + "\n";
}

}  // namespace mocapdb::json
