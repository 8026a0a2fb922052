#pragma once
// The byte-level primitives every binary format of the library writes and reads (internal, not
// installed): zigzag codes, LEB128 varints and little-endian fixed-width integers. Readers take the
// caller's byte source, so that each format keeps its own bounds checks and error messages.
#include <cstdint>
#include <optional>
#include <vector>

namespace mocapdb::byte_stream {

/// Zigzag code of a signed integer (0, -1, 1, -2, ... -> 0, 1, 2, 3, ...) and back.
inline std::uint64_t zigzag(std::int64_t v) {
    return (static_cast<std::uint64_t>(v) << 1) ^ static_cast<std::uint64_t>(v >> 63);
}
inline std::int64_t unzigzag(std::uint64_t u) {
    return static_cast<std::int64_t>(u >> 1) ^ -static_cast<std::int64_t>(u & 1);
}

/// Appends v as a LEB128 varint (7 bits a byte, low first; the high bit marks a byte that follows).
inline void put_varint(std::vector<std::uint8_t>& out, std::uint64_t v) {
    while (v >= 0x80) {
        out.push_back(static_cast<std::uint8_t>(v | 0x80));
        v >>= 7;
    }
    out.push_back(static_cast<std::uint8_t>(v));
}

/// Reads a LEB128 varint, one byte at a time from next_byte() (which throws where the bytes end);
/// nullopt when it runs past 64 bits (malformed).
template <class NextByte>
std::optional<std::uint64_t> read_varint(NextByte&& next_byte) {
    std::uint64_t v = 0;
    for (int shift = 0; shift < 64; shift += 7) {
        const std::uint8_t b = next_byte();
        v |= static_cast<std::uint64_t>(b & 0x7F) << shift;
        if ((b & 0x80) == 0) return v;
    }
    return std::nullopt;
}

/// Appends the low `n` bytes of v, least significant first.
inline void put_le(std::vector<std::uint8_t>& out, std::uint64_t v, int n) {
    for (int i = 0; i < n; ++i) out.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
}

/// The `n` bytes at p as a little-endian unsigned integer.
inline std::uint64_t get_le(const std::uint8_t* p, int n) {
    std::uint64_t v = 0;
    for (int i = 0; i < n; ++i) v |= static_cast<std::uint64_t>(p[i]) << (8 * i);
    return v;
}

}  // namespace mocapdb::byte_stream
