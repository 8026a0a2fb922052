#pragma once
// Static canonical Huffman codes of the runtime tier (internal to the packing module): lengths from
// counts (limited to a maximum), canonical codes, the stored form of a code (its lengths) and a
// checked symbol reader for what is decoded once at construction.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "runtime_bits.hpp"

namespace mocapdb::packing::detail {

/// Code lengths (0: symbol unused) of a Huffman code for `counts` (one per symbol of the alphabet),
/// each at most max_length (rarest codes lengthened until Kraft's sum is <= 1). One used symbol: 1.
std::vector<std::uint8_t> rt_code_lengths(const std::vector<std::size_t>& counts, int max_length);

/// Canonical codes (by length, then symbol) of `lengths`; unused symbols get 0.
std::vector<std::uint32_t> rt_canonical_codes(const std::vector<std::uint8_t>& lengths);

/// The stored form of a code over an alphabet of lengths.size() symbols (< 2^bits_per_symbol
/// symbols; lengths < 16): 2 bits of mode (0 no symbol, 1 every length at 4 bits, 2 a count and the
/// used symbols with their lengths), whichever is smaller.
void rt_write_lengths(RtBitWriter& out, const std::vector<std::uint8_t>& lengths, int bits_per_symbol);
/// Reads what rt_write_lengths wrote; throws Error (naming in.what) when the lengths are longer than
/// max_length or over-subscribe the code (Kraft's sum above 1).
std::vector<std::uint8_t> rt_read_lengths(RtCheckedReader& in, std::size_t alphabet, int bits_per_symbol,
                                          int max_length);

/// A canonical code read symbol by symbol from a checked reader (construction-time side data).
class RtSlowCode {
public:
    explicit RtSlowCode(const std::vector<std::uint8_t>& lengths);
    /// The next symbol; throws Error when the bits are no code.
    int read(RtCheckedReader& in) const;

private:
    std::vector<int> sorted_;                           ///< symbols in canonical order
    std::vector<std::uint32_t> first_, count_, index_;  ///< per length
};

}  // namespace mocapdb::packing::detail
