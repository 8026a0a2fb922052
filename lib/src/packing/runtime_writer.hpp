#pragma once
// The runtime body's writer (internal to the packing module): the quantized transform of a group
// (runtime_transform.hpp) as the bytes runtime_layout.hpp describes: keys at per-clip widths with
// centers and escapes, detail columns by quads under static canonical codes per (level, row >> 3)
// trained on the group, a directory of `stored` levels, per-clip packed entry offsets.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "runtime_layout.hpp"

namespace mocapdb::packing::detail {

/// Where the body's bytes went (sum: the body's size).
struct RuntimeBodyParts {
    std::size_t header = 0, side = 0, offsets = 0, entries = 0, slack = 0;
};

/// The body of `r` for Da active dofs; `stored` directory levels (0 .. r.levels - 1). Throws
/// PackingFailed when a value does not fit the format (a key row wider than 40 bits, a quad wider than
/// 32 bits, more than 2^32 entry bytes).
std::vector<std::uint8_t> write_runtime_body(const RuntimeCoefficients& r, int Da, int stored,
                                             RuntimeBodyParts* parts = nullptr);

}  // namespace mocapdb::packing::detail
