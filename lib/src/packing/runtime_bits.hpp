#pragma once
// Bit I/O of the runtime tier (internal to the packing module): an MSB-first writer, a checked reader
// for parsing at construction (throws on a read past its end), and the unchecked readers of the hot
// path, which read 8 bytes at a time and rely on the body's trailing slack (kRuntimeSlack bytes).
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "mocapdb/core/error.hpp"

namespace mocapdb::packing::detail {

/// Zero bytes after the entries of a runtime body: the hot path's 8-byte reads never leave the body.
constexpr std::size_t kRuntimeSlack = 16;

/// Bits that hold v (0 for 0).
inline int rt_bit_length(std::uint64_t v) { return v ? 64 - __builtin_clzll(v) : 0; }

/// Two's complement bits that hold q (0 for 0).
inline int rt_twos_bits(std::int64_t q) {
    if (!q) return 0;
    return rt_bit_length(static_cast<std::uint64_t>(q < 0 ? ~q : q)) + 1;
}

/// MSB-first bit writer.
struct RtBitWriter {
    std::vector<std::uint8_t> bytes;
    std::uint64_t acc = 0;
    int n = 0;
    void put(std::uint64_t value, int bits) {
        if (bits == 0) return;
        if (bits > 32) {
            put(value >> 32, bits - 32);
            bits = 32;
        }
        acc = (acc << bits) | (value & ((std::uint64_t{1} << bits) - 1));
        n += bits;
        while (n >= 8) {
            bytes.push_back(static_cast<std::uint8_t>(acc >> (n - 8)));
            n -= 8;
        }
        acc &= (std::uint64_t{1} << n) - 1;
    }
    void align() {
        if (n > 0) put(0, 8 - n);
    }
    std::size_t bits() const { return bytes.size() * 8 + static_cast<std::size_t>(n); }
};

/// MSB-first reader over [data, data + size) that throws Error (naming `what`) on a read past the end.
struct RtCheckedReader {
    const std::uint8_t* data = nullptr;
    std::size_t size = 0;  ///< bytes
    std::size_t pos = 0;   ///< bits
    const char* what = "runtime body";
    std::uint64_t get(int bits) {
        if (bits == 0) return 0;
        if (bits > 57 || pos + static_cast<std::size_t>(bits) > 8 * size)
            throw Error(std::string(what) + ": truncated (a read of " + std::to_string(bits) + " bits at bit " +
                        std::to_string(pos) + " of " + std::to_string(8 * size) + ")");
        std::uint64_t v = 0;
        for (int k = 0; k < bits; ++k, ++pos) v = (v << 1) | ((data[pos >> 3] >> (7 - (pos & 7))) & 1u);
        return v;
    }
    std::int64_t get_signed(int bits) {
        if (bits == 0) return 0;
        const std::uint64_t v = get(bits);
        return static_cast<std::int64_t>(v << (64 - bits)) >> (64 - bits);
    }
};

/// The 64 bits at bit p, MSB-first (8 bytes read from byte p / 8: the caller guarantees them).
inline std::uint64_t rt_peek(const std::uint8_t* data, std::size_t p) {
    std::uint64_t v;
    std::memcpy(&v, data + (p >> 3), 8);
    return __builtin_bswap64(v) << (p & 7);
}

/// w bits at bit p as a two's complement value (0 when w is 0; w <= 57).
inline std::int64_t rt_signed_bits(const std::uint8_t* data, std::size_t p, int w) {
    const std::uint64_t v = rt_peek(data, p);
    // Arithmetic shift of the top w bits (w 0: a shift by 63 and then by 1, never by 64).
    const auto q = static_cast<std::int64_t>(v) >> (63 - (w ? w - 1 : 63)) >> (w ? 0 : 1);
    return w ? q : 0;
}

/// w unsigned bits at bit p (0 <= w <= 57; 0 for w 0).
inline std::size_t rt_field(const std::uint8_t* data, std::size_t p, int w) {
    return static_cast<std::size_t>((rt_peek(data, p) >> 1) >> (63 - w));
}

/// w unsigned bits at bit p (1 <= w <= 57).
inline std::size_t rt_unsigned_bits(const std::uint8_t* data, std::size_t p, int w) {
    return static_cast<std::size_t>(rt_peek(data, p) >> (64 - w));
}

/// The decoder's bit buffer (a branch-free refill): buf holds the next bits MSB-first, at least 56 of
/// them after refill(); the loads do not depend on the bits decoded.
struct RtFastBits {
    const std::uint8_t* next = nullptr;
    std::uint64_t buf = 0;
    int avail = 0;  ///< bits in buf
    std::size_t consumed = 0;
    RtFastBits(const std::uint8_t* data, std::size_t bit) : next(data + (bit >> 3)) {
        refill();
        drop(static_cast<int>(bit & 7));
        consumed = bit;
    }
    void refill() {
        std::uint64_t v;
        std::memcpy(&v, next, 8);
        buf |= __builtin_bswap64(v) >> avail;
        next += (63 - avail) >> 3;
        avail |= 56;
    }
    void drop(int n) {
        buf <<= n;
        avail -= n;
        consumed += static_cast<std::size_t>(n);
    }
};

}  // namespace mocapdb::packing::detail
