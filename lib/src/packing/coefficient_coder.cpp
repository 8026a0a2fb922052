#include "mocapdb/packing/coefficient_coder.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace mocapdb::packing {
namespace {

// One traversal of the model, shared by the encoder, the counter and the decoder so that they
// cannot disagree: Sink::bit(ctx, bit) codes/counts/decodes one adaptive decision and returns it;
// Sink::direct(value, count) the same at probability 1/2.
template <class Sink>
std::uint32_t gamma(Sink& sink, BitContext* prefix, BitContext* msb, std::uint32_t value) {
    // value >= 1: n = floor(log2 value) as n ones and a zero, then the n low bits, the highest of
    // them adaptive (context msb[n]) when msb is given.
    int n = 0;
    if constexpr (Sink::kDecoding) {
        while (n < kGammaBits - 1 && sink.bit(prefix + n, 0)) ++n;
        if (msb == nullptr || n == 0) return (1u << n) | sink.direct(0, n);
        const auto top = static_cast<std::uint32_t>(sink.bit(msb + n, 0));
        return (1u << n) | (top << (n - 1)) | sink.direct(0, n - 1);
    } else {
        while ((value >> (n + 1)) != 0) ++n;
        for (int k = 0; k < n; ++k) sink.bit(prefix + k, 1);
        if (n < kGammaBits - 1) sink.bit(prefix + n, 0);
        if (msb == nullptr || n == 0) {
            sink.direct(value & ((1u << n) - 1u), n);
        } else {
            sink.bit(msb + n, static_cast<int>((value >> (n - 1)) & 1u));
            sink.direct(value & ((1u << (n - 1)) - 1u), n - 1);
        }
        return value;
    }
}

// `level` (size entries, zeroed by the caller): min(|q|, 2) by grid index.
// Returns the coded length (scan positions up to the last nonzero one; decoding: at most `size`).
// Decoding with `nonzero` given: the scan positions of the nonzero coefficients, in order, into it
// (their count into *nonzero_count).
template <class Sink>
std::size_t traverse(Sink& sink, ContextSet& ctx, const std::uint8_t* classes, std::size_t size, const ScanGrid& grid,
                     std::int32_t* q, std::uint8_t* level, std::uint32_t* nonzero = nullptr,
                     std::size_t* nonzero_count = nullptr) {
    std::size_t nonzeros = 0;
    const std::uint32_t* scan = grid.scan->data();
    const auto rows = static_cast<std::uint32_t>(grid.rows);
    std::uint32_t length = 0;
    if constexpr (!Sink::kDecoding) {
        for (std::size_t i = size; i-- > 0;)
            if (q[i] != 0) {
                length = static_cast<std::uint32_t>(i + 1);
                break;
            }
    }
    length = gamma(sink, ctx.length(), nullptr, length + 1) - 1;
    if constexpr (Sink::kDecoding) length = std::min<std::uint32_t>(length, static_cast<std::uint32_t>(size));
    int previous = 1;
    for (std::size_t i = 0; i < length; ++i) {
        const int cls = classes[i];
        const std::uint32_t pos = scan[i];
        const std::uint32_t r1 = pos % rows;
        const int n = std::min(4, (r1 > 0 ? level[pos - 1] : 0) + (pos >= rows ? level[pos - rows] : 0));
        const int nz = sink.bit(ctx.nonzero(cls, previous, n), q[i] != 0 ? 1 : 0);
        previous = nz;
        if (!nz) {
            if constexpr (Sink::kDecoding) q[i] = 0;
            continue;
        }
        const std::uint32_t negative = sink.direct(q[i] < 0 ? 1u : 0u, 1);
        const std::uint32_t magnitude = static_cast<std::uint32_t>(std::abs(q[i]));
        std::uint32_t m = 1;
        if (sink.bit(ctx.greater_one(cls, n), magnitude > 1 ? 1 : 0))
            m = gamma(sink, ctx.gamma(cls), ctx.gamma_msb(cls), magnitude - 1) + 1;
        level[pos] = static_cast<std::uint8_t>(std::min<std::uint32_t>(m, 2));
        if constexpr (Sink::kDecoding) {
            q[i] = negative ? -static_cast<std::int32_t>(m) : static_cast<std::int32_t>(m);
            if (nonzero != nullptr) nonzero[nonzeros++] = static_cast<std::uint32_t>(i);
        }
    }
    if (nonzero_count != nullptr) *nonzero_count = nonzeros;
    if constexpr (Sink::kDecoding)
        for (std::size_t i = length; i < size; ++i) q[i] = 0;
    return length;
}

struct EncodeSink {
    static constexpr bool kDecoding = false;
    RangeEncoder rc;
    int bit(BitContext* c, int b) {
        rc.encode(*c, b);
        return b;
    }
    std::uint32_t direct(std::uint32_t v, int n) {
        if (n > 16) {
            rc.encode_direct(v >> 16, n - 16);
            n = 16;
        }
        if (n > 0) rc.encode_direct(v & 0xFFFFu, n);
        return v;
    }
};

struct CountSink {
    static constexpr bool kDecoding = false;
    ContextCounts* counts;
    const BitContext* base;
    int bit(BitContext* c, int b) {
        ++counts->n[static_cast<std::size_t>(c - base)][static_cast<std::size_t>(b)];
        return b;
    }
    std::uint32_t direct(std::uint32_t v, int) { return v; }
};

struct DecodeSink {
    static constexpr bool kDecoding = true;
    RangeDecoder rc;
    int bit(BitContext* c, int) { return rc.decode(*c); }
    std::uint32_t direct(std::uint32_t, int n) {
        std::uint32_t high = 0;
        if (n > 16) {
            high = rc.decode_direct(n - 16) << 16;
            n = 16;
        }
        return high | (n > 0 ? rc.decode_direct(n) : 0u);
    }
};

}  // namespace

ContextSet ContextCounts::to_contexts() const {
    ContextSet out;
    for (std::size_t i = 0; i < n.size(); ++i) {
        if (n[i][0] + n[i][1] == 0) continue;  // unused: stays at 1/2
        const double p0 = (static_cast<double>(n[i][0]) + 0.4) / (static_cast<double>(n[i][0] + n[i][1]) + 0.8);
        // 8 bits of precision (what a packed group stores), never exactly 1/2 (that means unused).
        long v = std::clamp(std::lround(p0 * 256.0), 1L, 255L);
        if (v == 128) v = p0 < 0.5 ? 127 : 129;
        out.p[i] = static_cast<BitContext>(v << (kProbabilityBits - 8));
    }
    return out;
}

std::vector<double> class_levels(const std::vector<float>& sigma) {
    std::vector<double> out(sigma.size());
    for (std::size_t i = 0; i < sigma.size(); ++i)
        out[i] = sigma[i] > 0 ? 2.0 * std::log2(static_cast<double>(sigma[i])) : -1e30;
    return out;
}

void position_classes(const std::vector<double>& levels, double step, std::vector<std::uint8_t>& out_classes) {
    out_classes.resize(levels.size());
    const double offset = kClassBias - 2.0 * std::log2(step);
    for (std::size_t i = 0; i < levels.size(); ++i) {
        const double c = std::floor(levels[i] + offset);
        out_classes[i] = static_cast<std::uint8_t>(c <= 0 ? 0 : c >= kClasses - 1 ? kClasses - 1 : c);
    }
}

std::vector<std::uint32_t> identity_scan(std::size_t size) {
    std::vector<std::uint32_t> out(size);
    for (std::size_t i = 0; i < size; ++i) out[i] = static_cast<std::uint32_t>(i);
    return out;
}

std::vector<std::uint8_t> encode_coefficients(const std::vector<std::int32_t>& q,
                                              const std::vector<std::uint8_t>& classes, const ScanGrid& grid,
                                              ContextSet contexts) {
    EncodeSink sink;
    std::vector<std::int32_t> copy(q);
    copy.resize(classes.size(), 0);  // q may stop after its last nonzero
    std::vector<std::uint8_t> level(classes.size(), 0);
    traverse(sink, contexts, classes.data(), classes.size(), grid, copy.data(), level.data());
    return sink.rc.finish();
}

void count_coefficients(const std::vector<std::int32_t>& q, const std::vector<std::uint8_t>& classes,
                        const ScanGrid& grid, ContextCounts& counts) {
    ContextSet contexts;
    CountSink sink{&counts, contexts.p.data()};
    std::vector<std::int32_t> copy(q);
    copy.resize(classes.size(), 0);
    std::vector<std::uint8_t> level(classes.size(), 0);
    traverse(sink, contexts, classes.data(), classes.size(), grid, copy.data(), level.data());
}

void decode_coefficients(const std::uint8_t* data, std::size_t size, const std::vector<std::uint8_t>& classes,
                         const ScanGrid& grid, ContextSet contexts, std::vector<std::int32_t>& out_q) {
    out_q.resize(classes.size());
    std::vector<std::uint8_t> level(classes.size(), 0);
    decode_coefficients(data, size, classes.data(), classes.size(), grid, contexts, out_q.data(), level.data());
}

std::size_t decode_coefficients(const std::uint8_t* data, std::size_t size, const std::uint8_t* classes,
                                std::size_t count, const ScanGrid& grid, ContextSet& contexts, std::int32_t* out_q,
                                std::uint8_t* level, std::uint32_t* nonzero, std::size_t* nonzero_count) {
    DecodeSink sink{RangeDecoder(data, size)};
    std::fill(level, level + count, std::uint8_t(0));
    return traverse(sink, contexts, classes, count, grid, out_q, level, nonzero, nonzero_count);
}

}  // namespace mocapdb::packing
