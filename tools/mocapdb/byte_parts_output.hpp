#pragma once
// Printing a packing::ByteParts (bytes per kind of stored data): as a JSON object in the parts'
// order (its values sum to the bytes it describes) and as one line of text.
#include <string>

#include "json_writer.hpp"
#include "mocapdb/packing/byte_parts.hpp"

namespace mocapdb::cli {

/// Writes key "parts" and the object {name: bytes, ...}.
inline void write_parts_json(JsonWriter& j, const packing::ByteParts& parts) {
    j.key("parts").begin_object();
    for (const packing::BytePart& p : parts) j.key(p.name).value(static_cast<std::size_t>(p.bytes));
    j.end_object();
}

/// "topology 812, skeletons 1 520, ..." (parts with bytes only).
inline std::string parts_text(const packing::ByteParts& parts) {
    std::string out;
    for (const packing::BytePart& p : parts)
        if (p.bytes > 0) out += (out.empty() ? "" : ", ") + p.name + " " + std::to_string(p.bytes);
    return out;
}

}  // namespace mocapdb::cli
