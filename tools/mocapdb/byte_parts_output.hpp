#pragma once
// Printing a packing::ByteParts (bytes per kind of stored data): as a JSON object in the parts'
// order (its values sum to the bytes it describes) and as one line of text.
#include <string>

#include "mocapdb/packing/byte_parts.hpp"

namespace mocapdb::cli {

/// Writes key "parts" and the object {name: bytes, ...}.
/// "topology 812, skeletons 1 520, ..." (parts with bytes only).
inline std::string parts_text(const packing::ByteParts& parts) {
    std::string out;
    for (const packing::BytePart& p : parts)
        if (p.bytes > 0) out += (out.empty() ? "" : ", ") + p.name + " " + std::to_string(p.bytes);
    return out;
}

}  // namespace mocapdb::cli
