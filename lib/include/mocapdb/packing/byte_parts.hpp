#pragma once
// Where stored bytes go: an ordered list of named parts (one per kind of stored data) whose values
// sum exactly to the bytes they describe. The packed group's writer names its parts (packed_group.hpp,
// PackStats::parts); sums over groups keep the order of first appearance. Front-ends print a
// ByteParts as a JSON object in this order. Plain values; no state.
#include <cstdint>
#include <string>
#include <vector>

namespace mocapdb::packing {

struct BytePart {
    std::string name;  ///< e.g. "topology", "payload"
    std::uint64_t bytes = 0;
};

using ByteParts = std::vector<BytePart>;

/// Adds `bytes` to the part `name` (a new part is appended, even with 0 bytes).
inline void add_part(ByteParts& parts, const std::string& name, std::uint64_t bytes) {
    for (BytePart& p : parts)
        if (p.name == name) {
            p.bytes += bytes;
            return;
        }
    parts.push_back({name, bytes});
}

/// Adds every part of `more` to `parts` by name.
inline void add_parts(ByteParts& parts, const ByteParts& more) {
    for (const BytePart& p : more) add_part(parts, p.name, p.bytes);
}

/// The sum of the parts.
inline std::uint64_t total_bytes(const ByteParts& parts) {
    std::uint64_t sum = 0;
    for (const BytePart& p : parts) sum += p.bytes;
    return sum;
}

}  // namespace mocapdb::packing
