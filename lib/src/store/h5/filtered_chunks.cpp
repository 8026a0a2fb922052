#include "filtered_chunks.hpp"

#include <zlib.h>

namespace mocapdb::store::h5 {

std::uint32_t fletcher32(const std::uint8_t* data, std::size_t bytes) {
    constexpr std::size_t kWordsPerFold = 360;  // the sums cannot overflow 32 bits within a block
    const auto fold = [](std::uint32_t s) { return (s & 0xffffu) + (s >> 16); };
    std::uint32_t low = 0, high = 0;
    std::size_t words = bytes / 2;
    while (words > 0) {
        const std::size_t block = words < kWordsPerFold ? words : kWordsPerFold;
        words -= block;
        for (std::size_t i = 0; i < block; ++i, data += 2) {
            low += (static_cast<std::uint32_t>(data[0]) << 8) | static_cast<std::uint32_t>(data[1]);
            high += low;
        }
        low = fold(low);
        high = fold(high);
    }
    if (bytes % 2 != 0) {
        low += static_cast<std::uint32_t>(data[0]) << 8;
        high += low;
        low = fold(low);
        high = fold(high);
    }
    low = fold(low);
    high = fold(high);
    return (high << 16) | low;
}

std::vector<std::uint8_t> encode_filtered_chunk(const std::uint8_t* data, std::size_t bytes, std::size_t element_size,
                                                bool shuffle, int level) {
    std::vector<std::uint8_t> shuffled;
    const std::uint8_t* source = data;
    if (shuffle && element_size > 1) {
        const std::size_t elements = bytes / element_size;
        shuffled.resize(bytes);
        for (std::size_t e = 0; e < elements; ++e)
            for (std::size_t k = 0; k < element_size; ++k) shuffled[k * elements + e] = data[e * element_size + k];
        // A tail shorter than an element stays where it is (whole elements here; kept for the contract).
        for (std::size_t i = elements * element_size; i < bytes; ++i) shuffled[i] = data[i];
        source = shuffled.data();
    }
    uLongf size = compressBound(static_cast<uLong>(bytes));
    std::vector<std::uint8_t> out(size + 4);
    if (compress2(out.data(), &size, source, static_cast<uLong>(bytes), level) != Z_OK) return {};
    const std::uint32_t sum = fletcher32(out.data(), size);
    for (int b = 0; b < 4; ++b) out[size + static_cast<std::size_t>(b)] = static_cast<std::uint8_t>(sum >> (8 * b));
    out.resize(size + 4);
    return out;
}

}  // namespace mocapdb::store::h5
