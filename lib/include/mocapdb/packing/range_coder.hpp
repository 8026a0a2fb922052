#pragma once
// A binary adaptive range coder (the carry-less LZMA scheme): each binary decision is coded with a
// probability that adapts to the decisions seen in its context. Used to entropy-code one window of
// quantized coefficients on its own, so that windows decode independently (random access).
//
// Contract: a RangeDecoder over the bytes of a finished RangeEncoder, fed the same sequence of
// decode calls with contexts initialised to the same values, returns the encoded bits. The decoder
// reads zero bytes past the end of its input, which lets finish() drop trailing zero bytes.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace mocapdb::packing {

/// Probability that the next bit is 0, in units of 1 / kProbabilityOne.
using BitContext = std::uint16_t;
constexpr int kProbabilityBits = 15;
constexpr BitContext kProbabilityOne = BitContext(1u << kProbabilityBits);
constexpr BitContext kProbabilityHalf = BitContext(1u << (kProbabilityBits - 1));
/// Adaptation speed: after each bit the probability moves 1 / 2^kAdaptShift of the way to it.
constexpr int kAdaptShift = 5;

class RangeEncoder {
public:
    /// Codes `bit` (0 or 1) with context `ctx` and adapts it.
    void encode(BitContext& ctx, int bit);
    /// Codes the low `count` bits of `value` (most significant first) at probability 1/2, count <= 24.
    void encode_direct(std::uint32_t value, int count);
    /// Ends the stream; returns its bytes (trailing zero bytes removed). The encoder is then spent.
    std::vector<std::uint8_t> finish();

private:
    void shift_low();
    std::uint64_t low_ = 0;
    std::uint32_t range_ = 0xFFFFFFFFu;
    std::uint8_t cache_ = 0;
    std::uint64_t cache_size_ = 1;
    bool first_ = true;  // the first byte LZMA's scheme emits is always 0: not stored
    std::vector<std::uint8_t> out_;
};

class RangeDecoder {
public:
    /// Decodes from `size` bytes at `data` (not copied: must outlive the decoder).
    RangeDecoder(const std::uint8_t* data, std::size_t size);
    // Inline: called once per coded decision, the decoder's inner loop.
    int decode(BitContext& ctx) {
        const std::uint32_t bound = (range_ >> kProbabilityBits) * ctx;
        int bit;
        if (code_ < bound) {
            range_ = bound;
            ctx = static_cast<BitContext>(ctx + ((kProbabilityOne - ctx) >> kAdaptShift));
            bit = 0;
        } else {
            code_ -= bound;
            range_ -= bound;
            ctx = static_cast<BitContext>(ctx - (ctx >> kAdaptShift));
            bit = 1;
        }
        normalize();
        return bit;
    }
    std::uint32_t decode_direct(int count) {
        std::uint32_t value = 0;
        while (count-- > 0) {
            range_ >>= 1;
            const std::uint32_t bit = code_ >= range_ ? 1u : 0u;
            code_ -= range_ & (0u - bit);
            value = (value << 1) | bit;
            normalize();
        }
        return value;
    }

private:
    static constexpr std::uint32_t kTop = 1u << 24;
    std::uint8_t next() { return pos_ < size_ ? data_[pos_++] : std::uint8_t(0); }
    void normalize() {
        while (range_ < kTop) {
            range_ <<= 8;
            code_ = (code_ << 8) | next();
        }
    }
    const std::uint8_t* data_;
    std::size_t size_;
    std::size_t pos_ = 0;
    std::uint32_t range_ = 0xFFFFFFFFu;
    std::uint32_t code_ = 0;
};

}  // namespace mocapdb::packing
