// Lossless channel packing: decimal detection, prediction along time, byte planes, zstd.
// Layout of the decompressed payload (schemas/format-v3.md §5), channel-major, frames in order:
//   1. residuals: the zigzag codes u of the coarse integers' prediction residuals as byte planes: one
//                 width byte W (0..8) per decimal channel, then plane 0 (least significant bytes) of
//                 every decimal channel with W > 0, plane 1 of those with W > 1, ..., F bytes each;
//   2. extra:     per decimal channel, F bytes: extra decimals e (0..22-k), 0xFE exception, 0xFF -0.0;
//   3. refine:    per value with e >= 1, a zigzag varint r (N = c * 10^e + r, d = k + e);
//   4. raw:       per raw channel, 8 byte planes (most significant first) of F bytes of the float64
//                 bits xor-ed with the previous frame's; then 8 little-endian bytes per exception.
#include "mocapdb/packing/lossless_channels.hpp"

#include <zstd.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include "../core/byte_stream.hpp"
#include "mocapdb/core/error.hpp"

namespace mocapdb::packing {
namespace {

constexpr int kMaxDecimals = 22;                      // 10^22 is the largest power of ten a double holds exactly
constexpr double kExactInteger = 9007199254740992.0;  // 2^53: integers below convert exactly
constexpr std::uint8_t kException = 0xFE;
constexpr std::uint8_t kNegativeZero = 0xFF;

const std::array<double, kMaxDecimals + 1>& powers_of_ten() {
    static const std::array<double, kMaxDecimals + 1> p = [] {
        std::array<double, kMaxDecimals + 1> out{};
        double v = 1.0;
        for (double& x : out) {
            x = v;
            v *= 10.0;  // exact up to 10^22
        }
        return out;
    }();
    return p;
}

// 10^e as an integer (e <= 18 fits int64).
std::int64_t int_power_of_ten(int e) {
    std::int64_t p = 1;
    for (int i = 0; i < e; ++i) p *= 10;
    return p;
}

std::uint64_t bits_of(double x) {
    std::uint64_t b;
    std::memcpy(&b, &x, sizeof b);
    return b;
}

double from_bits(std::uint64_t b) {
    double x;
    std::memcpy(&x, &b, sizeof x);
    return x;
}

// The decoder's formula, used by the encoder to verify: the reader computed v * scale with v the
// correctly rounded decimal, which is double(n) / 10^d when |n| < 2^53.
double decimal_value(std::int64_t n, int d, double scale) {
    return (static_cast<double>(n) / powers_of_ten()[static_cast<std::size_t>(d)]) * scale;
}

using byte_stream::put_varint;
using byte_stream::unzigzag;
using byte_stream::zigzag;

// Order-p prediction of v[t] from earlier values (0 before the first frame).
// Wrapping arithmetic: valid data stays far below 2^63, and corrupt data must not be undefined behaviour.
std::int64_t predict(const std::int64_t* v, std::size_t t, int order) {
    if (t == 0) return 0;
    if (order == 1 || t == 1) return v[t - 1];
    return static_cast<std::int64_t>(2 * static_cast<std::uint64_t>(v[t - 1]) - static_cast<std::uint64_t>(v[t - 2]));
}

std::int64_t wrapping_add(std::int64_t a, std::int64_t b) {
    return static_cast<std::int64_t>(static_cast<std::uint64_t>(a) + static_cast<std::uint64_t>(b));
}

// Smallest decimal count d with (double(n) / 10^d) * scale == x bitwise; false when none exists.
struct Decimal {
    std::int64_t n = 0;
    int d = 0;
};
bool shortest_decimal(double x, double scale, Decimal& out) {
    if (!std::isfinite(x) || (x == 0.0 && std::signbit(x))) return false;
    const double v = x / scale;
    for (int d = 0; d <= kMaxDecimals; ++d) {
        const double t = v * powers_of_ten()[static_cast<std::size_t>(d)];
        if (!(std::fabs(t) < kExactInteger)) return false;
        const auto n = static_cast<std::int64_t>(std::llround(t));
        if (bits_of(decimal_value(n, d, scale)) == bits_of(x)) {
            out = {n, d};
            return true;
        }
    }
    return false;
}

// One channel as coarse integers c at base count k, extra decimals e and refinements r.
struct DecimalChannel {
    int k = 0;
    int order = 1;
    std::vector<std::int64_t> coarse;
    std::vector<std::uint8_t> extra;
    std::vector<std::int64_t> refine;  // one per value with 1 <= e <= 22
    std::size_t cost = 0;              // estimated bits after zstd
};

enum class Kind : std::uint8_t { Decimal, NegativeZero, Exception };

// Splits the channel at base count k; false when some coarse integer would not be exact.
bool split(const std::vector<Kind>& kind, const std::vector<Decimal>& dec, int k, DecimalChannel& out) {
    const std::size_t f = kind.size();
    out.k = k;
    out.coarse.assign(f, 0);
    out.extra.assign(f, 0);
    out.refine.clear();
    std::int64_t previous = 0;
    for (std::size_t t = 0; t < f; ++t) {
        if (kind[t] != Kind::Decimal) {
            out.coarse[t] = previous;  // keeps the prediction smooth across the marker
            out.extra[t] = kind[t] == Kind::NegativeZero ? kNegativeZero : kException;
            continue;
        }
        const Decimal& v = dec[t];
        if (v.d <= k) {
            const double scaled = static_cast<double>(v.n) * powers_of_ten()[static_cast<std::size_t>(k - v.d)];
            if (!(std::fabs(scaled) < kExactInteger)) return false;
            out.coarse[t] = v.n * int_power_of_ten(k - v.d);
        } else {
            const int e = v.d - k;
            out.extra[t] = static_cast<std::uint8_t>(e);
            // |n| < 2^53 < 10^16: from e = 16 on the coarse part is 0.
            const std::int64_t p = e < 16 ? int_power_of_ten(e) : 0;
            out.coarse[t] = p == 0 ? 0 : v.n / p;
            out.refine.push_back(p == 0 ? v.n : v.n - out.coarse[t] * p);
        }
        previous = out.coarse[t];
    }
    return true;
}

// Significant bits of u (0 for 0): the estimate of what zstd's entropy stage leaves of a code.
std::size_t bit_length(std::uint64_t u) { return u == 0 ? 0 : static_cast<std::size_t>(64 - __builtin_clzll(u)); }

std::size_t residual_cost(const std::vector<std::int64_t>& c, int order) {
    std::size_t bits = 0;
    for (std::size_t t = 0; t < c.size(); ++t) bits += bit_length(zigzag(c[t] - predict(c.data(), t, order)));
    return bits;
}

// Estimated bits of the decimal form at its best k and order; false when no k is usable.
bool best_decimal_form(const std::vector<Kind>& kind, const std::vector<Decimal>& dec, const LosslessOptions& o,
                       DecimalChannel& best) {
    bool found = false;
    DecimalChannel trial;
    for (int k = 0; k <= o.max_decimals; ++k) {
        if (!split(kind, dec, k, trial)) continue;
        std::size_t side = 0;
        for (const std::int64_t r : trial.refine) side += bit_length(zigzag(r)) + 1;
        for (std::size_t t = 1; t < trial.extra.size(); ++t) side += trial.extra[t] != trial.extra[t - 1] ? 8 : 0;
        for (const Kind x : kind) side += x == Kind::Exception ? 64 : 0;
        for (const int order : {1, 2}) {
            if (o.predictor != 0 && order != o.predictor) continue;
            const std::size_t cost = side + residual_cost(trial.coarse, order);
            if (!found || cost < best.cost) {
                found = true;
                trial.order = order;
                trial.cost = cost;
                best = trial;
            }
        }
    }
    return found;
}

// Estimated bits of the float64 bits xor-ed with the previous frame's (significant bits, as above).
std::size_t raw_cost(const FrameMatrix& m, Eigen::Index col) {
    std::size_t bits = 0;
    std::uint64_t previous = 0;
    for (Eigen::Index t = 0; t < m.rows(); ++t) {
        const std::uint64_t b = bits_of(m(t, col));
        bits += bit_length(b ^ previous);
        previous = b;
    }
    return bits;
}

// The LEB128 varints of one payload section, never read past its end.
class VarintReader {
public:
    VarintReader(const std::uint8_t* data, std::size_t size, const char* section)
        : p_(data), end_(data + size), section_(section) {}
    std::uint64_t varint() {
        if (const auto u = byte_stream::read_varint([this] { return byte(); })) return *u;
        throw Error(std::string("lossless channels: malformed varint in the ") + section_ + " section");
    }
    std::uint8_t byte() {
        if (p_ == end_) throw Error(std::string("lossless channels: the ") + section_ + " section ends early");
        return *p_++;
    }
    bool done() const { return p_ == end_; }

private:
    const std::uint8_t* p_;
    const std::uint8_t* end_;
    const char* section_;
};

// The residual section back to one zigzag code per frame and decimal channel.
std::vector<std::vector<std::uint64_t>> residual_planes(const std::uint8_t* p, std::size_t size, std::size_t channels,
                                                        std::size_t frames) {
    if (size < channels) throw Error("lossless channels: the residual section ends early");
    std::size_t expected = channels;
    for (std::size_t i = 0; i < channels; ++i) {
        if (p[i] > 8) throw Error("lossless channels: residual width " + std::to_string(p[i]) + " (expected 0..8)");
        expected += p[i] * frames;
    }
    if (expected != size)
        throw Error("lossless channels: the residual section has " + std::to_string(size) + " bytes, its widths say " +
                    std::to_string(expected));
    std::vector<std::vector<std::uint64_t>> out(channels, std::vector<std::uint64_t>(frames, 0));
    const std::uint8_t* b = p + channels;
    for (int plane = 0; plane < 8; ++plane)
        for (std::size_t i = 0; i < channels; ++i)
            if (p[i] > plane)
                for (std::uint64_t& u : out[i]) u |= static_cast<std::uint64_t>(*b++) << (8 * plane);
    return out;
}

}  // namespace

std::vector<double> reader_scales(const Skeleton& s) {
    std::vector<double> out(s.channel_count());
    const double angle = s.source_units().degrees ? kPi / 180.0 : 1.0;
    for (std::size_t j = 0; j < s.size(); ++j)
        for (std::size_t k = 0; k < s.joint(j).channels.size(); ++k)
            out[s.first_channel(j) + k] = is_rotation(s.joint(j).channels[k]) ? angle : s.source_units().cm_per_unit;
    return out;
}

PackedChannels pack_channels(const FrameMatrix& channels, const std::vector<double>& scales,
                             const LosslessOptions& options) {
    const auto f = static_cast<std::size_t>(channels.rows());
    const auto nc = static_cast<std::size_t>(channels.cols());
    if (f == 0) throw InvalidArgument("pack_channels: expected at least one frame, found 0");
    if (scales.size() != nc)
        throw InvalidArgument("pack_channels: expected " + std::to_string(nc) + " scales (one per channel), found " +
                              std::to_string(scales.size()));
    for (const double s : scales)
        if (!(s > 0.0) || !std::isfinite(s)) throw InvalidArgument("pack_channels: scales must be positive and finite");
    if (options.zstd_level < 1 || options.zstd_level > ZSTD_maxCLevel())
        throw InvalidArgument("pack_channels: zstd_level must be in 1.." + std::to_string(ZSTD_maxCLevel()));
    if (options.predictor < 0 || options.predictor > 2)
        throw InvalidArgument("pack_channels: predictor must be 0, 1 or 2");
    if (options.max_decimals < 0 || options.max_decimals > 18)
        throw InvalidArgument("pack_channels: max_decimals must be in 0..18");

    PackedChannels out;
    out.frames = f;
    out.scale = scales;
    out.decimals.assign(nc, kRawChannel);
    out.predictor.assign(nc, 1);
    std::vector<std::uint8_t> extra, refine, raw, exceptions;
    std::vector<std::vector<std::uint64_t>> zigzags;  // per decimal channel
    std::vector<std::size_t> raw_columns;

    std::vector<Kind> kind(f);
    std::vector<Decimal> dec(f);
    for (std::size_t j = 0; j < nc; ++j) {
        const auto col = static_cast<Eigen::Index>(j);
        for (std::size_t t = 0; t < f && options.detect_decimals; ++t) {
            const double x = channels(static_cast<Eigen::Index>(t), col);
            if (shortest_decimal(x, scales[j], dec[t])) kind[t] = Kind::Decimal;
            else kind[t] = bits_of(x) == bits_of(-0.0) ? Kind::NegativeZero : Kind::Exception;
        }
        DecimalChannel best;
        if (!options.detect_decimals || !best_decimal_form(kind, dec, options, best) ||
            best.cost >= raw_cost(channels, col)) {
            raw_columns.push_back(j);
            continue;
        }
        out.decimals[j] = best.k;
        out.predictor[j] = best.order;
        std::size_t next_refinement = 0;
        std::vector<std::uint64_t>& z = zigzags.emplace_back(f);
        for (std::size_t t = 0; t < f; ++t) {
            z[t] = zigzag(best.coarse[t] - predict(best.coarse.data(), t, best.order));
            extra.push_back(best.extra[t]);
            if (best.extra[t] == kException) {
                const std::uint64_t b = bits_of(channels(static_cast<Eigen::Index>(t), col));
                for (int i = 0; i < 8; ++i) exceptions.push_back(static_cast<std::uint8_t>(b >> (8 * i)));
            } else if (best.extra[t] != 0 && best.extra[t] != kNegativeZero) {
                put_varint(refine, zigzag(best.refine[next_refinement++]));
            }
        }
    }
    for (const std::size_t j : raw_columns) {
        const auto col = static_cast<Eigen::Index>(j);
        for (int plane = 7; plane >= 0; --plane) {
            std::uint64_t previous = 0;
            for (std::size_t t = 0; t < f; ++t) {
                const std::uint64_t b = bits_of(channels(static_cast<Eigen::Index>(t), col));
                raw.push_back(static_cast<std::uint8_t>((b ^ previous) >> (8 * plane)));
                previous = b;
            }
        }
    }
    raw.insert(raw.end(), exceptions.begin(), exceptions.end());
    // Byte planes rather than varints: the high planes are nearly constant and zstd's entropy stage
    // codes the noisy low planes on their own statistics (docs/storage.md has the measurement).
    std::vector<std::uint8_t> residuals;
    std::vector<int> widths;
    for (const auto& z : zigzags) {
        int w = 0;
        for (std::uint64_t m = *std::max_element(z.begin(), z.end()); m != 0; m >>= 8) ++w;
        widths.push_back(w);
        residuals.push_back(static_cast<std::uint8_t>(w));
    }
    for (int plane = 0; plane < 8; ++plane)
        for (std::size_t i = 0; i < zigzags.size(); ++i)
            if (widths[i] > plane)
                for (const std::uint64_t u : zigzags[i])
                    residuals.push_back(static_cast<std::uint8_t>(u >> (8 * plane)));
    out.section_bytes = {residuals.size(), extra.size(), refine.size(), raw.size()};

    std::vector<std::uint8_t> payload;
    payload.reserve(residuals.size() + extra.size() + refine.size() + raw.size());
    for (const auto* s : {&residuals, &extra, &refine, &raw}) payload.insert(payload.end(), s->begin(), s->end());

    ZSTD_CCtx* cctx = ZSTD_createCCtx();
    if (cctx == nullptr) throw Error("pack_channels: cannot create a zstd context");
    ZSTD_CCtx_setParameter(cctx, ZSTD_c_compressionLevel, options.zstd_level);
    ZSTD_CCtx_setParameter(cctx, ZSTD_c_checksumFlag, 1);
    out.bytes.resize(ZSTD_compressBound(payload.size()));
    const std::size_t n = ZSTD_compress2(cctx, out.bytes.data(), out.bytes.size(), payload.data(), payload.size());
    ZSTD_freeCCtx(cctx);
    if (ZSTD_isError(n)) throw Error(std::string("pack_channels: zstd failed: ") + ZSTD_getErrorName(n));
    out.bytes.resize(n);
    out.bytes.shrink_to_fit();

    // Never lossy: the stored form must decode to the same bits.
    const FrameMatrix back = unpack_channels(out);
    for (Eigen::Index i = 0; i < channels.size(); ++i)
        if (bits_of(back.data()[i]) != bits_of(channels.data()[i]))
            throw Error("pack_channels: the packed channels do not decode exactly (value " + std::to_string(i) +
                        "); this is a bug");
    return out;
}

FrameMatrix unpack_channels(const PackedChannels& packed) {
    const std::size_t f = packed.frames;
    const std::size_t nc = packed.channels();
    if (f == 0) throw Error("lossless channels: expected at least one frame, found 0");
    if (packed.decimals.size() != nc || packed.predictor.size() != nc)
        throw Error("lossless channels: expected " + std::to_string(nc) +
                    " decimals and predictors (one per scale), found " + std::to_string(packed.decimals.size()) +
                    " and " + std::to_string(packed.predictor.size()));
    std::size_t decimal_channels = 0;
    for (std::size_t j = 0; j < nc; ++j) {
        const std::string who = "lossless channels: channel " + std::to_string(j) + ": ";
        if (!(packed.scale[j] > 0.0) || !std::isfinite(packed.scale[j]))
            throw Error(who + "expected a positive finite scale, found " + std::to_string(packed.scale[j]));
        if (packed.decimals[j] != kRawChannel && (packed.decimals[j] < 0 || packed.decimals[j] > kMaxDecimals))
            throw Error(who + "expected decimals -1 or 0..22, found " + std::to_string(packed.decimals[j]));
        if (packed.predictor[j] != 1 && packed.predictor[j] != 2)
            throw Error(who + "expected predictor 1 or 2, found " + std::to_string(packed.predictor[j]));
        if (packed.decimals[j] != kRawChannel) ++decimal_channels;
    }
    const std::size_t raw_channels = nc - decimal_channels;
    if (packed.section_bytes[1] != decimal_channels * f || packed.section_bytes[3] < raw_channels * f * 8)
        throw Error("lossless channels: section sizes do not match " + std::to_string(f) + " frames of " +
                    std::to_string(decimal_channels) + " decimal and " + std::to_string(raw_channels) +
                    " raw channels");
    std::uint64_t total = 0;
    for (const std::uint64_t s : packed.section_bytes) total += s;
    const unsigned long long content = ZSTD_getFrameContentSize(packed.bytes.data(), packed.bytes.size());
    if (content == ZSTD_CONTENTSIZE_ERROR || content == ZSTD_CONTENTSIZE_UNKNOWN || content != total)
        throw Error("lossless channels: expected a zstd frame of " + std::to_string(total) + " bytes, found " +
                    (content == ZSTD_CONTENTSIZE_ERROR || content == ZSTD_CONTENTSIZE_UNKNOWN
                         ? std::string("none")
                         : std::to_string(content)));
    std::vector<std::uint8_t> payload(static_cast<std::size_t>(total));
    const std::size_t n = ZSTD_decompress(payload.data(), payload.size(), packed.bytes.data(), packed.bytes.size());
    if (ZSTD_isError(n) || n != total)
        throw Error(std::string("lossless channels: zstd cannot decode the bytes: ") +
                    (ZSTD_isError(n) ? ZSTD_getErrorName(n) : "short frame"));
    const std::uint8_t* p = payload.data();
    const std::vector<std::vector<std::uint64_t>> zigzags =
        residual_planes(p, static_cast<std::size_t>(packed.section_bytes[0]), decimal_channels, f);
    const std::uint8_t* extra = p + packed.section_bytes[0];
    VarintReader refine(extra + packed.section_bytes[1], packed.section_bytes[2], "refinements");
    const std::uint8_t* raw = extra + packed.section_bytes[1] + packed.section_bytes[2];
    const std::uint8_t* exceptions = raw + raw_channels * f * 8;
    const std::uint8_t* exceptions_end = raw + packed.section_bytes[3];

    FrameMatrix out(static_cast<Eigen::Index>(f), static_cast<Eigen::Index>(nc));
    std::vector<std::int64_t> coarse(f);
    std::size_t raw_index = 0, decimal_index = 0;
    for (std::size_t j = 0; j < nc; ++j) {
        const auto col = static_cast<Eigen::Index>(j);
        if (packed.decimals[j] == kRawChannel) {
            const std::uint8_t* planes = raw + raw_index++ * f * 8;
            std::uint64_t previous = 0;
            for (std::size_t t = 0; t < f; ++t) {
                std::uint64_t x = 0;
                for (int plane = 7; plane >= 0; --plane)
                    x |= static_cast<std::uint64_t>(planes[static_cast<std::size_t>(7 - plane) * f + t]) << (8 * plane);
                previous ^= x;
                out(static_cast<Eigen::Index>(t), col) = from_bits(previous);
            }
            continue;
        }
        const int k = static_cast<int>(packed.decimals[j]);
        const int order = static_cast<int>(packed.predictor[j]);
        const std::vector<std::uint64_t>& z = zigzags[decimal_index++];
        for (std::size_t t = 0; t < f; ++t) coarse[t] = wrapping_add(unzigzag(z[t]), predict(coarse.data(), t, order));
        for (std::size_t t = 0; t < f; ++t) {
            const std::uint8_t e = *extra++;
            double x;
            if (e == kNegativeZero) {
                x = -0.0;
            } else if (e == kException) {
                if (exceptions_end - exceptions < 8) throw Error("lossless channels: the raw section ends early");
                std::uint64_t b = 0;
                for (int i = 0; i < 8; ++i) b |= static_cast<std::uint64_t>(*exceptions++) << (8 * i);
                x = from_bits(b);
            } else {
                if (k + e > kMaxDecimals)
                    throw Error("lossless channels: channel " + std::to_string(j) + " frame " + std::to_string(t) +
                                ": expected at most " + std::to_string(kMaxDecimals - k) + " extra decimals, found " +
                                std::to_string(e));
                std::int64_t value = coarse[t];
                if (e > 0) {
                    const std::int64_t r = unzigzag(refine.varint());
                    // Beyond 10^18 the coarse part is 0 by construction; anything else is corrupt.
                    const bool bad = e > 18 ? coarse[t] != 0
                                            : __builtin_mul_overflow(coarse[t], int_power_of_ten(e), &value) ||
                                                  __builtin_add_overflow(value, r, &value);
                    if (e > 18 && !bad) value = r;
                    if (bad) throw Error("lossless channels: channel " + std::to_string(j) + ": integer out of range");
                }
                if (!(std::fabs(static_cast<double>(value)) < kExactInteger))
                    throw Error("lossless channels: channel " + std::to_string(j) + ": integer out of range");
                x = decimal_value(value, k + e, packed.scale[j]);
            }
            out(static_cast<Eigen::Index>(t), col) = x;
        }
    }
    if (!refine.done() || exceptions != exceptions_end)
        throw Error("lossless channels: the payload has bytes left over after decoding");
    return out;
}

}  // namespace mocapdb::packing
