#include "mocapdb/packing/range_coder.hpp"

namespace mocapdb::packing {
namespace {
constexpr std::uint32_t kTop = 1u << 24;
}

void RangeEncoder::shift_low() {
    if (static_cast<std::uint32_t>(low_) < 0xFF000000u || (low_ >> 32) != 0) {
        const auto carry = static_cast<std::uint8_t>(low_ >> 32);
        std::uint8_t temp = cache_;
        do {
            if (first_) first_ = false;  // always 0 + carry 0: the decoder assumes it
            else out_.push_back(static_cast<std::uint8_t>(temp + carry));
            temp = 0xFF;
        } while (--cache_size_ != 0);
        cache_ = static_cast<std::uint8_t>(low_ >> 24);
    }
    ++cache_size_;
    low_ = (low_ & 0x00FFFFFFu) << 8;
}

void RangeEncoder::encode(BitContext& ctx, int bit) {
    const std::uint32_t bound = (range_ >> kProbabilityBits) * ctx;
    if (bit == 0) {
        range_ = bound;
        ctx = static_cast<BitContext>(ctx + ((kProbabilityOne - ctx) >> kAdaptShift));
    } else {
        low_ += bound;
        range_ -= bound;
        ctx = static_cast<BitContext>(ctx - (ctx >> kAdaptShift));
    }
    while (range_ < kTop) {
        range_ <<= 8;
        shift_low();
    }
}

void RangeEncoder::encode_direct(std::uint32_t value, int count) {
    while (count-- > 0) {
        range_ >>= 1;
        if ((value >> count) & 1u) low_ += range_;
        while (range_ < kTop) {
            range_ <<= 8;
            shift_low();
        }
    }
}

std::vector<std::uint8_t> RangeEncoder::finish() {
    // Any value in [low, low + range) decodes the same; pick the one with the most trailing zero
    // bits so that more trailing zero bytes can be dropped (the decoder reads zeros past the end).
    for (int bits = 32; bits > 0; --bits) {
        const std::uint64_t mask = (std::uint64_t(1) << bits) - 1;
        const std::uint64_t v = (low_ + mask) & ~mask;
        if (v >= low_ && v - low_ < range_) {
            low_ = v;
            break;
        }
    }
    for (int i = 0; i < 5; ++i) shift_low();
    while (!out_.empty() && out_.back() == 0) out_.pop_back();
    return std::move(out_);
}

RangeDecoder::RangeDecoder(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {
    for (int i = 0; i < 4; ++i) code_ = (code_ << 8) | next();
}

}  // namespace mocapdb::packing
