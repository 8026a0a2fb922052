#include "mocapdb/packing/runtime_decoder.hpp"

#include <algorithm>
#include <cstring>
#include <limits>
#include <string>

#include "group_model.hpp"
#include "runtime_bits.hpp"
#include "runtime_codes.hpp"
#include "runtime_layout.hpp"
#include "runtime_pose_plan.hpp"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace mocapdb::packing {

using namespace detail;

namespace detail {

/// A key row of a clip's plan: its slot's byte and shifts (value = (bswap(8 bytes at byte) << shl) >>
/// sar, arithmetic), its row, and whether it has escapes.
struct RtPlanRow {
    std::uint16_t byte, d;
    std::uint8_t shl, sar, escapes;
};

/// Per clip: where its entries' offsets are, its key plan's counts, its directory widths.
struct RtClipInfo {
    std::int64_t origin = 0;  ///< entry k's byte offset in the entries: origin + k · slope + its field
    std::uint32_t slope = 0;
    std::uint32_t at = 0;         ///< bit of its entries' offset fields in the offset stream
    std::uint32_t entries = 0;    ///< entries (windows + 1)
    std::uint16_t slot_bits = 0;  ///< the keys' step field and slots (escaped values follow)
    std::uint16_t plain = 0;      ///< plan rows of nonzero width without escapes
    std::uint16_t nonzero = 0;    ///< plan rows of nonzero width
    std::uint8_t offset_width = 0;
    std::uint8_t by_clip = 0;  ///< directory widths below (else in each window)
    std::uint8_t widths[kMaxLevels + 1] = {};
    std::uint8_t step_base[kMaxLevels + 1] = {};  ///< step fields: 0 the key's, l level l's
    std::uint8_t step_width[kMaxLevels + 1] = {};
};

}  // namespace detail

namespace {

/// Per-thread buffers (sized on first use, reused).
struct RtScratch {
    std::vector<double> y, a, b, c, p, frames, row;
};
RtScratch& rt_scratch() {
    thread_local RtScratch s;
    return s;
}

}  // namespace

struct RuntimeDecoder::Impl {
    GroupModel model;
    RuntimePosePlan plan;
    const std::uint8_t* body = nullptr;
    std::size_t body_size = 0;
    const std::uint8_t* offsets = nullptr;  ///< offset stream
    const std::uint8_t* data = nullptr;     ///< entries
    std::size_t entry_bytes = 0;
    int W = 0, levels = 0, stored = 0, Da = 0, per_level = 0;
    std::vector<RtClipInfo> clips;
    std::vector<RtPlanRow> rows;         ///< per clip Da
    std::vector<std::int32_t> center;    ///< per clip Da
    std::vector<std::uint8_t> full;      ///< per clip Da: escape widths (rows with escapes)
    std::vector<std::uint8_t> width;     ///< per clip Da (the walk)
    std::vector<std::uint16_t> table;    ///< per quad context 2^kQuadCodeBits: bits 0-3 length, 4-13 pattern or
                                         ///< width, 14 wide, 15 end (0: no code)
    std::vector<std::int32_t> patterns;  ///< four values per pattern
    double steps[kMaxStep + 1] = {};     ///< step_of(k): a lookup instead of exp2 on the hot path

    void parse(const std::uint8_t* group, std::size_t group_size, bool allow_avx2);
    void walk() const;
    std::size_t entry_offset(std::size_t clip, std::size_t k) const {
        const RtClipInfo& c = clips[clip];
        return static_cast<std::size_t>(
            c.origin + static_cast<std::int64_t>(k * c.slope) +
            static_cast<std::int64_t>(rt_field(offsets, c.at + k * c.offset_width, c.offset_width)));
    }

    // The hot path (no checks: the walk at construction made every read stay in the body).
    void key_one(std::size_t clip, std::size_t at, double* out) const;
    std::size_t key_pair(std::size_t clip, std::size_t at_a, std::size_t at_b, double* a, double* b) const;
    std::size_t read_quads(std::size_t pos, int level, std::int32_t* q) const;
    std::size_t skip_quads(std::size_t pos, int level) const;
    std::size_t skip_subtree(std::size_t pos, int level) const;
    std::size_t directory(std::size_t clip, std::size_t pos, int t, std::size_t* skip) const;
    /// A window's steps and predictors per level (step[1 .. levels], predictor[1 .. levels]) from its
    /// step fields at bit pos; returns the bit after them.
    std::size_t window_steps(std::size_t clip, std::size_t pos, double* step, int* predictor) const {
        const RtClipInfo& c = clips[clip];
        const std::size_t f = rt_field(data, pos, c.step_width[1]);
        step[1] = steps[c.step_base[1] + f];
        predictor[1] = 0;
        pos += c.step_width[1];
        for (int l = 2; l <= levels; ++l) {
            const auto v = static_cast<unsigned>(rt_field(data, pos, c.step_width[l]));
            step[l] = steps[c.step_base[l] + v / kRuntimePredictors];
            predictor[l] = static_cast<int>(v % kRuntimePredictors);
            pos += c.step_width[l];
        }
        return pos;
    }
    void path(std::size_t clip, std::size_t bit, int t, double* y, double* a, double* b, double* c) const;
    void frame_y(std::size_t clip, std::size_t frame, double* y, double* a, double* b, double* c) const;
    /// Window w's W + 1 frames of y (frames: (W + 1) · Da values).
    void window_y(std::size_t clip, std::size_t w, double* frames) const;

    /// Calls fn(frame, y) for frames [begin, end) of a clip, decoding each window once.
    template <class Fn>
    void each_frame(std::size_t clip, std::size_t begin, std::size_t end, Fn fn) const {
        RtScratch& s = rt_scratch();
        prepare(s);
        const auto n = static_cast<std::size_t>(Da);
        const auto w_frames = static_cast<std::size_t>(W);
        s.frames.resize((w_frames + 1) * n);
        std::size_t loaded = ~std::size_t{0};
        for (std::size_t f = begin; f < end; ++f) {
            const std::size_t w = f / w_frames, t = f % w_frames;
            if (t == 0) {
                // A key: the window's first frame (or the clip's end key).
                key_one(clip, entry_offset(clip, w), s.y.data());
                fn(f, s.y.data());
                continue;
            }
            if (loaded != w) {
                window_y(clip, w, s.frames.data());
                loaded = w;
            }
            fn(f, s.frames.data() + t * n);
        }
    }

    void check(std::size_t clip) const {
        if (clip >= clips.size())
            throw InvalidArgument("RuntimeDecoder: clip " + std::to_string(clip) + " of " +
                                  std::to_string(clips.size()));
    }
    void check(std::size_t clip, std::size_t frame) const {
        check(clip);
        if (frame >= model.clips[clip].frames)
            throw InvalidArgument("RuntimeDecoder: frame " + std::to_string(frame) + " of " +
                                  std::to_string(model.clips[clip].frames));
    }
    void prepare(RtScratch& s) const {
        const auto n = static_cast<std::size_t>(std::max(Da, 4));
        if (s.y.size() < n) {
            s.y.resize(n);
            s.a.resize(n);
            s.b.resize(n);
            s.c.resize(n);
        }
        if (s.p.size() < static_cast<std::size_t>(model.dofs)) s.p.resize(static_cast<std::size_t>(model.dofs));
    }
};

namespace {

std::uint32_t rt_read_u32(const std::uint8_t* p) {
    return static_cast<std::uint32_t>(p[0]) | static_cast<std::uint32_t>(p[1]) << 8 |
           static_cast<std::uint32_t>(p[2]) << 16 | static_cast<std::uint32_t>(p[3]) << 24;
}

#if defined(__SSE2__)
/// Two rows: out = p + v · s where v (from q) is nonzero, else p (zeros add nothing, as the encoder forms it).
inline void rt_store_residual(double* out, __m128d p, const std::int32_t* q, __m128d s) {
    const __m128d v = _mm_cvtepi32_pd(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(q)));
    const __m128d nonzero = _mm_cmpneq_pd(v, _mm_setzero_pd());
    const __m128d sum = _mm_add_pd(p, _mm_mul_pd(v, s));
    _mm_storeu_pd(out, _mm_or_pd(_mm_and_pd(nonzero, sum), _mm_andnot_pd(nonzero, p)));
}
#endif

/// out[d] = p + q[d] * step where q[d] is nonzero, else p, with p = 0.5 * (lo[d] + hi[d]): the
/// encoder's expressions (SSE2 two rows at a time: the same operations, a select instead of a branch).
inline void rt_combine(double* out, const double* lo, const double* hi, const std::int32_t* q, double step, int Da) {
    int d = 0;
#if defined(__SSE2__)
    const __m128d half = _mm_set1_pd(0.5), s = _mm_set1_pd(step);
    for (; d + 2 <= Da; d += 2) {
        const __m128d p = _mm_mul_pd(half, _mm_add_pd(_mm_loadu_pd(lo + d), _mm_loadu_pd(hi + d)));
        rt_store_residual(out + d, p, q + d, s);
    }
#endif
    for (; d < Da; ++d) {
        const double p = 0.5 * (lo[d] + hi[d]);
        out[d] = q[d] ? p + q[d] * step : p;
    }
}

/// out[d] = p + q[d] * step where q[d] is nonzero, else p, with p = w[0] · near[d] + w[1] · far[d] +
/// w[2] · third[d] in that order (the encoder's predictor). out may be third.
inline void rt_combine3(double* out, const double* near, const double* far, const double* third, const std::int32_t* q,
                        double step, const double* w, int Da) {
    int d = 0;
#if defined(__SSE2__)
    const __m128d w0 = _mm_set1_pd(w[0]), w1 = _mm_set1_pd(w[1]), w2 = _mm_set1_pd(w[2]), s = _mm_set1_pd(step);
    for (; d + 2 <= Da; d += 2) {
        const __m128d p =
            _mm_add_pd(_mm_add_pd(_mm_mul_pd(w0, _mm_loadu_pd(near + d)), _mm_mul_pd(w1, _mm_loadu_pd(far + d))),
                       _mm_mul_pd(w2, _mm_loadu_pd(third + d)));
        rt_store_residual(out + d, p, q + d, s);
    }
#endif
    for (; d < Da; ++d) {
        const double p = w[0] * near[d] + w[1] * far[d] + w[2] * third[d];
        out[d] = q[d] ? p + q[d] * step : p;
    }
}

}  // namespace

void RuntimeDecoder::Impl::parse(const std::uint8_t* group, std::size_t group_size, bool allow_avx2) {
    const std::size_t header_end = model.read_header(group, group_size);
    if (model.runtime != (body == nullptr))
        throw Error(model.runtime ? "runtime body: a runtime group holds its own body, none is expected beside it"
                                  : "runtime body: none given for a packed group of format 3");
    if (model.runtime) {
        body = group + header_end;
        body_size = group_size - header_end;
        if (runtime_body_crc(body, body_size) != model.body_crc)
            throw Error("runtime body: checksum mismatch (the bytes are damaged)");
    }
    // What only format 3's windows need.
    model.windows = {};
    model.time_basis.resize(0, 0);
    model.scan = {};
    model.scan_row = {};
    model.sigma = {};
    model.levels = {};
    model.dof_energy = {};
    model.time_energy = {};
    if (body_size < kRuntimeHeaderBytes + kRuntimeSlack)
        throw Error("runtime body: " + std::to_string(body_size) + " bytes, expected at least " +
                    std::to_string(kRuntimeHeaderBytes + kRuntimeSlack));
    if (body[0] != kRuntimeVersion)
        throw Error("runtime body: version " + std::to_string(body[0]) + ", expected " +
                    std::to_string(kRuntimeVersion));
    levels = body[1];
    stored = body[2];
    if (levels < 1 || levels > kMaxLevels || stored >= levels)
        throw Error("runtime body: " + std::to_string(levels) + " levels and " + std::to_string(stored) +
                    " directory levels, expected 1-5 levels and fewer directory levels");
    W = 1 << levels;
    Da = body[4] | body[5] << 8;
    if (static_cast<std::size_t>(Da) != model.active.size())
        throw Error("runtime body: " + std::to_string(Da) + " active dofs, the packed group has " +
                    std::to_string(model.active.size()));
    const std::size_t clip_count = rt_read_u32(body + 8);
    if (clip_count != model.clips.size())
        throw Error("runtime body: " + std::to_string(clip_count) + " clips, the packed group has " +
                    std::to_string(model.clips.size()));
    const std::size_t side_bytes = rt_read_u32(body + 12), offset_bytes = rt_read_u32(body + 16);
    entry_bytes = rt_read_u32(body + 20);
    if (kRuntimeHeaderBytes + side_bytes + offset_bytes + entry_bytes + kRuntimeSlack != body_size)
        throw Error("runtime body: " + std::to_string(body_size) + " bytes, its header gives " +
                    std::to_string(kRuntimeHeaderBytes + side_bytes + offset_bytes + entry_bytes + kRuntimeSlack));
    const std::uint8_t* side = body + kRuntimeHeaderBytes;
    offsets = side + side_bytes;
    data = offsets + offset_bytes;
    make_runtime_pose_plan(model, allow_avx2, plan);
    for (int k = 0; k <= kMaxStep; ++k) steps[k] = step_of(k);

    RtCheckedReader in{side, side_bytes, 0, "runtime body (side stream)"};
    // Quad codes.
    per_level = quad_contexts_per_level(Da);
    const std::size_t contexts = static_cast<std::size_t>(levels * per_level), n = std::size_t{1} << kQuadCodeBits;
    table.assign(contexts * n, 0);
    for (std::size_t c = 0; c < contexts; ++c) {
        const auto lengths = rt_read_lengths(in, kQuadAlphabet, kQuadSymbolBits, kQuadCodeBits);
        if (lengths[kQuadWideSymbol] || lengths[kQuadWideSymbol + 1])
            throw Error("runtime body: a quad code for values of width 0 or 1, expected widths 2-32");
        const auto codes = rt_canonical_codes(lengths);
        for (int s = 0; s < kQuadAlphabet; ++s) {
            const int l = lengths[static_cast<std::size_t>(s)];
            if (!l) continue;
            std::uint32_t e = static_cast<std::uint32_t>(l);
            if (s == kQuadEndSymbol) e |= 1u << 15;
            else if (s >= kQuadWideSymbol) e |= static_cast<std::uint32_t>(s - kQuadWideSymbol) << 4 | 1u << 14;
            else e |= static_cast<std::uint32_t>(s - 1) << 4;
            const std::size_t base = static_cast<std::size_t>(codes[static_cast<std::size_t>(s)])
                                     << (kQuadCodeBits - l);
            for (std::size_t k = 0; k < (std::size_t{1} << (kQuadCodeBits - l)); ++k)
                table[c * n + base + k] = static_cast<std::uint16_t>(e);
        }
    }
    patterns.assign(4 * kQuadPatterns, 0);
    for (int p = 0; p < kQuadPatterns; ++p)
        for (int k = 3, x = p; k >= 0; --k, x /= 3) patterns[static_cast<std::size_t>(4 * p + k)] = x % 3 - 1;
    // Key rows.
    const auto rowsn = static_cast<std::size_t>(Da);
    std::vector<int> largest(rowsn);
    for (auto& l : largest) {
        l = static_cast<int>(in.get(kSideSymbolBits));
        if (l > kKeyMaxWidth)
            throw Error("runtime body: a key width of " + std::to_string(l) + " bits, expected at most 40");
    }
    const RtSlowCode delta_code(rt_read_lengths(in, kSideAlphabet, kSideSymbolBits, kSideCodeBits));
    const RtSlowCode center_code(rt_read_lengths(in, kSideAlphabet, kSideSymbolBits, kSideCodeBits));
    const RtSlowCode extra_code(rt_read_lengths(in, kSideAlphabet, kSideSymbolBits, kSideCodeBits));
    clips.assign(clip_count, RtClipInfo{});
    width.assign(clip_count * rowsn, 0);
    full.assign(clip_count * rowsn, 0);
    center.assign(clip_count * rowsn, 0);
    rows.clear();
    rows.reserve(clip_count * rowsn);
    for (std::size_t i = 0; i < clip_count; ++i) {
        RtClipInfo& c = clips[i];
        for (int l = 0; l <= levels; ++l) {
            c.step_base[l] = static_cast<std::uint8_t>(in.get(8));
            c.step_width[l] = static_cast<std::uint8_t>(in.get(4));
            if (c.step_base[l] > kMaxStep || c.step_width[l] > 10)
                throw Error("runtime body: clip " + std::to_string(i) + " step field " + std::to_string(l) +
                            ": base above 254 or width above 10 bits");
        }
        // The key's step field, then its slots.
        std::uint32_t slots = c.step_width[0];
        std::vector<std::uint16_t> at(rowsn);
        for (std::size_t d = 0; d < rowsn; ++d) {
            const int w = largest[d] - delta_code.read(in);
            const int cw = center_code.read(in);
            const std::int64_t ce = in.get_signed(cw);
            const int f = w + extra_code.read(in);
            if (w < 0 || f > kKeyMaxWidth || (w == 0 && f != 0) || cw > 32 ||
                ce < std::numeric_limits<std::int32_t>::min() || ce > std::numeric_limits<std::int32_t>::max())
                throw Error("runtime body: clip " + std::to_string(i) + " key row " + std::to_string(d) +
                            ": width, escape width or center out of range");
            width[i * rowsn + d] = static_cast<std::uint8_t>(w);
            full[i * rowsn + d] = static_cast<std::uint8_t>(f);
            center[i * rowsn + d] = static_cast<std::int32_t>(ce);
            at[d] = static_cast<std::uint16_t>(slots);
            slots += static_cast<std::uint32_t>(w);
        }
        c.slot_bits = static_cast<std::uint16_t>(slots);
        // The plan: rows of nonzero width without escapes, then with escapes (each ascending), then width 0.
        std::uint16_t count[3] = {0, 0, 0};
        for (int pass = 0; pass < 3; ++pass)
            for (std::size_t d = 0; d < rowsn; ++d) {
                const int w = width[i * rowsn + d];
                const bool escapes = full[i * rowsn + d] > w;
                if ((w == 0 ? 2 : escapes ? 1 : 0) != pass) continue;
                rows.push_back({static_cast<std::uint16_t>(at[d] >> 3), static_cast<std::uint16_t>(d),
                                static_cast<std::uint8_t>(at[d] & 7), static_cast<std::uint8_t>(64 - w),
                                static_cast<std::uint8_t>(escapes)});
                ++count[pass];
            }
        c.plain = count[0];
        c.nonzero = static_cast<std::uint16_t>(count[0] + count[1]);
    }
    std::size_t offset_bit = 0;
    for (std::size_t i = 0; i < clip_count; ++i) {
        RtClipInfo& c = clips[i];
        c.by_clip = static_cast<std::uint8_t>(in.get(1));
        if (c.by_clip)
            for (int l = 1; l <= stored; ++l) c.widths[l] = static_cast<std::uint8_t>(in.get(5));
        c.origin = in.get_signed(34);
        c.slope = static_cast<std::uint32_t>(in.get(24));
        c.offset_width = static_cast<std::uint8_t>(in.get(6));
        c.entries = static_cast<std::uint32_t>(runtime_entry_count(model.clips[i].frames, W));
        c.at = static_cast<std::uint32_t>(offset_bit);
        if (c.offset_width > 32)
            throw Error("runtime body: clip " + std::to_string(i) + " offsets of " + std::to_string(c.offset_width) +
                        " bits, expected at most 32");
        offset_bit += c.entries * static_cast<std::size_t>(c.offset_width);
        if (offset_bit > 8 * offset_bytes)
            throw Error("runtime body: the offsets of clip " + std::to_string(i) + " pass the offset stream's " +
                        std::to_string(offset_bytes) + " bytes");
    }
    walk();
}

void RuntimeDecoder::Impl::walk() const {
    // Every entry, clip by clip: its offset, key, directory and columns parsed with checks; each
    // directory size equal to the subtree it skips; each entry ending where the next begins.
    std::vector<int> tree_level, tree_frame;
    runtime_tree_order(W, tree_level, tree_frame);
    const auto rowsn = static_cast<std::size_t>(Da);
    const std::size_t n = std::size_t{1} << kQuadCodeBits;
    std::size_t expected = 0;  // where the next entry must start
    std::vector<std::size_t> column_bits(tree_level.size());
    for (std::size_t i = 0; i < clips.size(); ++i) {
        const RtClipInfo& c = clips[i];
        for (std::size_t k = 0; k < c.entries; ++k) {
            const std::size_t start = entry_offset(i, k);
            const std::string where = "runtime body: clip " + std::to_string(i) + " entry " + std::to_string(k);
            if (start != expected)
                throw Error(where + " at byte " + std::to_string(start) + ", expected " + std::to_string(expected));
            std::size_t pos = 8 * start;
            const std::size_t limit = 8 * entry_bytes;
            auto need = [&](std::size_t bits) {
                if (pos + bits > limit) throw Error(where + ": truncated (passes the entries' end)");
            };
            need(c.slot_bits);
            if (c.step_base[0] + rt_field(data, pos, c.step_width[0]) > kMaxStep)
                throw Error(where + ": key step above 254");
            std::size_t escape_bits = 0;
            for (std::size_t d = 0, at = pos + c.step_width[0]; d < rowsn; ++d) {
                const int w = width[i * rowsn + d];
                const std::int64_t v = rt_signed_bits(data, at, w);
                if (full[i * rowsn + d] > w && v == -(std::int64_t{1} << (w - 1))) escape_bits += full[i * rowsn + d];
                at += static_cast<std::size_t>(w);
            }
            pos += c.slot_bits;
            need(escape_bits);
            pos += escape_bits;
            if (k + 1 < c.entries) {
                for (int l = 1; l <= levels; ++l) {
                    need(c.step_width[l]);
                    const std::size_t f = rt_field(data, pos, c.step_width[l]);
                    if (c.step_base[l] + (l == 1 ? f : f / kRuntimePredictors) > kMaxStep)
                        throw Error(where + ": window step above 254");
                    pos += c.step_width[l];
                }
                int w[kMaxLevels + 1] = {0};
                for (int l = 1; l <= stored; ++l) {
                    if (c.by_clip) {
                        w[l] = c.widths[l];
                    } else {
                        need(5);
                        w[l] = static_cast<int>(rt_unsigned_bits(data, pos, 5));
                        pos += 5;
                    }
                }
                std::vector<std::size_t> sizes;
                for (int l = 1; l <= stored; ++l)
                    for (int node = 0; node < (1 << (l - 1)); ++node) {
                        need(static_cast<std::size_t>(w[l]));
                        sizes.push_back(w[l] ? rt_unsigned_bits(data, pos, w[l]) : 0);
                        pos += static_cast<std::size_t>(w[l]);
                    }
                // Columns in tree order.
                for (std::size_t col = 0; col < tree_level.size(); ++col) {
                    const std::size_t begin = pos;
                    const std::uint16_t* t =
                        table.data() + static_cast<std::size_t>((tree_level[col] - 1) * per_level) * n;
                    for (int d = 0; d < Da; d += 4) {
                        const std::uint32_t e = t[(static_cast<std::size_t>(d >> kQuadShift) * n) |
                                                  static_cast<std::size_t>(rt_peek(data, pos) >> (64 - kQuadCodeBits))];
                        if ((e & 15) == 0) throw Error(where + ": bits that are no quad code");
                        const std::size_t bits = (e & 15) + ((e >> 14) & 1) * 4 * ((e >> 4) & 1023);
                        need(bits);
                        pos += bits;
                        if (e & (1u << 15)) break;
                    }
                    column_bits[col] = pos - begin;
                }
                // The directory's sizes: level l's nodes' left subtrees, in tree order.
                for (std::size_t col = 0; col < tree_level.size(); ++col) {
                    const int l = tree_level[col];
                    if (l > stored) continue;
                    const std::size_t span = (std::size_t{1} << (levels - l)) - 1;
                    std::size_t left = 0;
                    for (std::size_t x = col + 1; x <= col + span; ++x) left += column_bits[x];
                    // Level l's sizes follow levels 1 .. l - 1's; node index within the level.
                    const std::size_t node = static_cast<std::size_t>(tree_frame[col]) >> (levels - l + 1);
                    const std::size_t index = ((std::size_t{1} << (l - 1)) - 1) + node;
                    if (sizes[index] != left)
                        throw Error(where + ": directory size " + std::to_string(sizes[index]) +
                                    " bits, the subtree has " + std::to_string(left));
                }
            }
            expected = (pos + 7) / 8;
        }
    }
    if (expected != entry_bytes)
        throw Error("runtime body: the entries end at byte " + std::to_string(expected) + " of " +
                    std::to_string(entry_bytes));
}

void RuntimeDecoder::Impl::key_one(std::size_t clip, std::size_t at, double* out) const {
    const auto n = static_cast<std::size_t>(Da);
    const RtClipInfo& c = clips[clip];
    const RtPlanRow* r = rows.data() + clip * n;
    const std::int32_t* ce = center.data() + clip * n;
    const double step = steps[c.step_base[0] + rt_field(data, 8 * at, c.step_width[0])];
    const std::uint8_t* pa = data + at;
    int escaped[kRuntimeMaxDofs];
    int ne = 0;
    for (int k = 0; k < c.nonzero; ++k) {
        std::uint64_t v;
        std::memcpy(&v, pa + r[k].byte, 8);
        const std::int64_t q = static_cast<std::int64_t>(__builtin_bswap64(v) << r[k].shl) >> r[k].sar;
        out[r[k].d] = static_cast<double>(q + ce[r[k].d]) * step;
        escaped[ne] = r[k].d;
        ne += static_cast<int>(r[k].escapes & (q == (std::numeric_limits<std::int64_t>::min() >> r[k].sar)));
    }
    for (int k = c.nonzero; k < Da; ++k) out[r[k].d] = static_cast<double>(std::int64_t{0} + ce[r[k].d]) * step;
    const std::uint8_t* f = full.data() + clip * n;
    std::size_t escape = 8 * at + c.slot_bits;
    for (int k = 0; k < ne; ++k) {
        const int d = escaped[k];
        out[d] = static_cast<double>(rt_signed_bits(data, escape, f[d]) + ce[d]) * step;
        escape += f[d];
    }
}

std::size_t RuntimeDecoder::Impl::key_pair(std::size_t clip, std::size_t at_a, std::size_t at_b, double* a,
                                           double* b) const {
    const auto n = static_cast<std::size_t>(Da);
    const RtClipInfo& c = clips[clip];
    const RtPlanRow* r = rows.data() + clip * n;
    const std::int32_t* ce = center.data() + clip * n;
    const double step_a = steps[c.step_base[0] + rt_field(data, 8 * at_a, c.step_width[0])],
                 step_b = steps[c.step_base[0] + rt_field(data, 8 * at_b, c.step_width[0])];
    const std::uint8_t* pa = data + at_a;
    const std::uint8_t* pb = data + at_b;
    auto row = [&](const RtPlanRow x, std::int64_t& qa, std::int64_t& qb) {
        std::uint64_t va, vb;
        std::memcpy(&va, pa + x.byte, 8);
        std::memcpy(&vb, pb + x.byte, 8);
        qa = static_cast<std::int64_t>(__builtin_bswap64(va) << x.shl) >> x.sar;
        qb = static_cast<std::int64_t>(__builtin_bswap64(vb) << x.shl) >> x.sar;
        a[x.d] = static_cast<double>(qa + ce[x.d]) * step_a;
        b[x.d] = static_cast<double>(qb + ce[x.d]) * step_b;
    };
    std::int64_t qa, qb;
    for (int k = 0; k < c.plain; ++k) row(r[k], qa, qb);
    int escaped_a[kRuntimeMaxDofs], escaped_b[kRuntimeMaxDofs];
    int na = 0, nb = 0;
    for (int k = c.plain; k < c.nonzero; ++k) {
        row(r[k], qa, qb);
        const std::int64_t code = std::numeric_limits<std::int64_t>::min() >> r[k].sar;  // -2^(w-1)
        escaped_a[na] = r[k].d;
        na += static_cast<int>(qa == code);
        escaped_b[nb] = r[k].d;
        nb += static_cast<int>(qb == code);
    }
    for (int k = c.nonzero; k < Da; ++k) {
        const int d = r[k].d;
        a[d] = static_cast<double>(std::int64_t{0} + ce[d]) * step_a;
        b[d] = static_cast<double>(std::int64_t{0} + ce[d]) * step_b;
    }
    const std::uint8_t* f = full.data() + clip * n;
    std::size_t escape_a = 8 * at_a + c.slot_bits, escape_b = 8 * at_b + c.slot_bits;
    for (int k = 0; k < nb; ++k) {
        const int d = escaped_b[k];
        b[d] = static_cast<double>(rt_signed_bits(data, escape_b, f[d]) + ce[d]) * step_b;
        escape_b += f[d];
    }
    for (int k = 0; k < na; ++k) {
        const int d = escaped_a[k];
        a[d] = static_cast<double>(rt_signed_bits(data, escape_a, f[d]) + ce[d]) * step_a;
        escape_a += f[d];
    }
    return escape_a;
}

std::size_t RuntimeDecoder::Impl::read_quads(std::size_t pos, int level, std::int32_t* q) const {
    constexpr int B = kQuadCodeBits;
    const std::uint16_t* t = table.data() + (static_cast<std::size_t>((level - 1) * per_level) << B);
    const std::int32_t* pat = patterns.data();
    RtFastBits bits(data, pos);
    int d = 0;
    while (d < Da) {
        bits.refill();
        const std::uint32_t e =
            t[(static_cast<std::size_t>(d >> kQuadShift) << B) | static_cast<std::size_t>(bits.buf >> (64 - B))];
        bits.drop(static_cast<int>(e & 15));
        if (__builtin_expect((e & 0xC000u) == 0, 1)) {
            std::memcpy(q + d, pat + 4 * ((e >> 4) & 1023), 4 * sizeof(std::int32_t));
            d += 4;
            continue;
        }
        if (e & (1u << 15)) break;
        const int wd = static_cast<int>((e >> 4) & 1023);
        if (wd <= 14) {
            bits.refill();
            const std::uint64_t x = bits.buf;
            for (int k = 0; k < 4; ++k)
                q[d + k] = static_cast<std::int32_t>(static_cast<std::int64_t>(x << (k * wd)) >> (64 - wd));
            bits.drop(4 * wd);
        } else {
            for (int k = 0; k < 4; ++k) {
                bits.refill();
                q[d + k] = static_cast<std::int32_t>(static_cast<std::int64_t>(bits.buf) >> (64 - wd));
                bits.drop(wd);
            }
        }
        d += 4;
    }
    for (; d < Da; ++d) q[d] = 0;
    return bits.consumed;
}

std::size_t RuntimeDecoder::Impl::skip_quads(std::size_t pos, int level) const {
    constexpr int B = kQuadCodeBits;
    const std::uint16_t* t = table.data() + (static_cast<std::size_t>((level - 1) * per_level) << B);
    for (int d = 0; d < Da; d += 4) {
        const std::uint32_t e = t[(static_cast<std::size_t>(d >> kQuadShift) << B) |
                                  static_cast<std::size_t>(rt_peek(data, pos) >> (64 - B))];
        pos += (e & 15) + ((e >> 14) & 1) * 4 * ((e >> 4) & 1023);
        if (e & (1u << 15)) break;
    }
    return pos;
}

std::size_t RuntimeDecoder::Impl::skip_subtree(std::size_t pos, int level) const {
    pos = skip_quads(pos, level);
    if (level < levels) {
        pos = skip_subtree(pos, level + 1);
        pos = skip_subtree(pos, level + 1);
    }
    return pos;
}

std::size_t RuntimeDecoder::Impl::directory(std::size_t clip, std::size_t pos, int t, std::size_t* skip) const {
    const RtClipInfo& c = clips[clip];
    int w[kMaxLevels + 1] = {0};
    for (int l = 1; l <= stored; ++l) {
        if (c.by_clip) {
            w[l] = c.widths[l];
        } else {
            w[l] = static_cast<int>(rt_unsigned_bits(data, pos, 5));
            pos += 5;
        }
    }
    for (int l = 1; l <= stored; ++l) {
        const std::size_t node = static_cast<std::size_t>(t) >> (levels - l + 1);
        skip[l] = w[l] ? rt_unsigned_bits(data, pos + node * static_cast<std::size_t>(w[l]), w[l]) : 0;
        pos += (std::size_t{1} << (l - 1)) * static_cast<std::size_t>(w[l]);
    }
    return pos;
}

void RuntimeDecoder::Impl::path(std::size_t clip, std::size_t bit, int t, double* y, double* a, double* b,
                                double* c) const {
    alignas(16) std::int32_t q[260];
    double step[kMaxLevels + 1];
    int predictor[kMaxLevels + 1];
    std::size_t skip[kMaxLevels + 1] = {0};
    std::size_t pos = directory(clip, window_steps(clip, bit, step, predictor), t, skip);
    int lo = 0, hi = W;
    double* lo_y = a;
    double* hi_y = b;
    // The parent interval's far end (none at level 1) and whether it lies beyond hi: a frame's
    // value is dead once its children are made, so each level writes over it.
    double* third = c;
    bool third_hi = false;
    for (int l = 1;; ++l) {
        const int mid = (lo + hi) / 2;
        double* out = mid == t ? y : third;
        pos = read_quads(pos, l, q);
        if (predictor[l] == 0) rt_combine(out, lo_y, hi_y, q, step[l], Da);
        else if (third_hi) rt_combine3(out, hi_y, lo_y, third, q, step[l], kRuntimePredictorWeights[predictor[l]], Da);
        else rt_combine3(out, lo_y, hi_y, third, q, step[l], kRuntimePredictorWeights[predictor[l]], Da);
        if (mid == t) return;
        if (t < mid) {
            third = hi_y;
            third_hi = true;
            hi = mid;
            hi_y = out;
        } else {
            pos = l <= stored ? pos + skip[l] : skip_subtree(pos, l + 1);
            third = lo_y;
            third_hi = false;
            lo = mid;
            lo_y = out;
        }
    }
}

void RuntimeDecoder::Impl::frame_y(std::size_t clip, std::size_t frame, double* y, double* a, double* b,
                                   double* c) const {
    const auto n = static_cast<std::size_t>(Da);
    {
        // The clip's key plan and centers: known before the entry's offset is.
        const auto* r = reinterpret_cast<const char*>(rows.data() + clip * n);
        for (std::size_t x = 0; x < n * sizeof(RtPlanRow); x += 64) __builtin_prefetch(r + x);
        const auto* ce = reinterpret_cast<const char*>(center.data() + clip * n);
        for (std::size_t x = 0; x < n * sizeof(std::int32_t); x += 64) __builtin_prefetch(ce + x);
        __builtin_prefetch(full.data() + clip * n);
    }
    const std::size_t w = frame >> levels;
    const int t = static_cast<int>(frame & static_cast<std::size_t>(W - 1));
    const RtClipInfo& ci = clips[clip];
    const std::size_t o0 = entry_offset(clip, w);
    if (t == 0) {
        key_one(clip, o0, y);
        return;
    }
    const std::size_t o1 = entry_offset(clip, w + 1);
    {
        // The window's bytes and the next key's: prefetched first, so that the misses overlap.
        const std::size_t end = o1 + ci.slot_bits / 8 + 8;
        for (std::size_t x = o0 & ~std::size_t{63}; x < end; x += 64) __builtin_prefetch(data + x);
    }
    path(clip, key_pair(clip, o0, o1, a, b), t, y, a, b, c);
}

void RuntimeDecoder::Impl::window_y(std::size_t clip, std::size_t w, double* frames) const {
    const auto n = static_cast<std::size_t>(Da);
    const std::size_t o0 = entry_offset(clip, w);
    const std::size_t o1 = entry_offset(clip, w + 1);
    const std::size_t bit = key_pair(clip, o0, o1, frames, frames + static_cast<std::size_t>(W) * n);
    double step[kMaxLevels + 1];
    int predictor[kMaxLevels + 1];
    std::size_t skip[kMaxLevels + 1] = {0};
    std::size_t pos = directory(clip, window_steps(clip, bit, step, predictor), 1, skip);
    alignas(16) std::int32_t q[260];
    struct Tree {
        const Impl& d;
        double* frames;
        std::size_t n;
        const double* step;
        const int* predictor;
        std::int32_t* q;
        std::size_t pos;
        double* at(int t) const { return frames + static_cast<std::size_t>(t) * n; }
        /// Interval [lo, hi] of a parent interval whose other end is `third` (-1 at level 1).
        void run(int lo, int hi, int third, int level) {
            if (hi - lo < 2) return;
            const int mid = (lo + hi) / 2;
            pos = d.read_quads(pos, level, q);
            const int p = predictor[level];
            if (p == 0) rt_combine(at(mid), at(lo), at(hi), q, step[level], d.Da);
            else if (third > hi)
                rt_combine3(at(mid), at(hi), at(lo), at(third), q, step[level], kRuntimePredictorWeights[p], d.Da);
            else rt_combine3(at(mid), at(lo), at(hi), at(third), q, step[level], kRuntimePredictorWeights[p], d.Da);
            run(lo, mid, hi, level + 1);
            run(mid, hi, lo, level + 1);
        }
    } tree{*this, frames, n, step, predictor, q, pos};
    tree.run(0, W, -1, 1);
}

RuntimeDecoder::RuntimeDecoder(const std::uint8_t* group, std::size_t group_size, const std::uint8_t* body,
                               std::size_t body_size, RuntimeKernels kernels)
    : impl_(std::make_unique<Impl>()) {
    if (!group || !body) throw InvalidArgument("RuntimeDecoder: null bytes");
    impl_->body = body;
    impl_->body_size = body_size;
    impl_->parse(group, group_size, kernels == RuntimeKernels::Automatic);
}
RuntimeDecoder::RuntimeDecoder(const std::uint8_t* group, std::size_t group_size, RuntimeKernels kernels)
    : impl_(std::make_unique<Impl>()) {
    if (!group) throw InvalidArgument("RuntimeDecoder: null bytes");
    impl_->parse(group, group_size, kernels == RuntimeKernels::Automatic);
}
RuntimeDecoder::~RuntimeDecoder() = default;
RuntimeDecoder::RuntimeDecoder(RuntimeDecoder&&) noexcept = default;
RuntimeDecoder& RuntimeDecoder::operator=(RuntimeDecoder&&) noexcept = default;

std::size_t RuntimeDecoder::clip_count() const { return impl_->clips.size(); }
std::size_t RuntimeDecoder::frame_count(std::size_t clip) const {
    impl_->check(clip);
    return impl_->model.clips[clip].frames;
}
double RuntimeDecoder::frame_rate() const { return impl_->model.frame_rate; }
std::size_t RuntimeDecoder::window_length() const { return static_cast<std::size_t>(impl_->W); }
bool RuntimeDecoder::uses_avx2() const { return impl_->plan.avx2; }
std::size_t RuntimeDecoder::clip_bytes(std::size_t clip) const {
    const Impl& d = *impl_;
    d.check(clip);
    const std::size_t end = clip + 1 < d.clips.size() ? d.entry_offset(clip + 1, 0) : d.entry_bytes;
    return end - d.entry_offset(clip, 0);
}

std::shared_ptr<const Skeleton> RuntimeDecoder::skeleton(std::size_t clip) const {
    impl_->check(clip);
    return impl_->model.skeletons[impl_->model.clips[clip].skeleton].skeleton;
}

std::size_t RuntimeDecoder::resident_bytes() const {
    const Impl& d = *impl_;
    const GroupModel& m = d.model;
    std::size_t total = sizeof(Impl);
    total += m.extra_columns.capacity() * sizeof(int) + m.active.capacity() * sizeof(int) +
             m.constant.capacity() * sizeof(double) + static_cast<std::size_t>(m.dof_basis.size()) * sizeof(double) +
             m.clips.capacity() * sizeof(ClipEntry);
    for (const SkeletonEntry& e : m.skeletons) {
        total += sizeof(e) + sizeof(Skeleton) + e.skeleton->size() * sizeof(Joint) +
                 static_cast<std::size_t>(e.weights.size()) * sizeof(double) +
                 e.active_weights.capacity() * sizeof(double) + e.stored_axes.capacity() * sizeof(e.stored_axes[0]) +
                 e.writer.memory_bytes();
        for (const Joint& j : e.skeleton->joints())
            total += j.name.capacity() + j.channels.capacity() * sizeof(ChannelType);
    }
    total += d.plan.memory_bytes();
    total += d.clips.capacity() * sizeof(RtClipInfo) + d.rows.capacity() * sizeof(RtPlanRow) +
             d.center.capacity() * sizeof(std::int32_t) + d.full.capacity() + d.width.capacity() +
             d.table.capacity() * sizeof(std::uint16_t) + d.patterns.capacity() * sizeof(std::int32_t);
    // One thread's scratch.
    const auto n = static_cast<std::size_t>(std::max(d.Da, 4));
    total += sizeof(RtScratch) + (4 * n + static_cast<std::size_t>(m.dofs)) * sizeof(double);
    return total;
}

void RuntimeDecoder::decode_local_pose(std::size_t clip, std::size_t frame, LocalPose& out) const {
    const Impl& d = *impl_;
    d.check(clip, frame);
    RtScratch& s = rt_scratch();
    d.prepare(s);
    d.frame_y(clip, frame, s.y.data(), s.a.data(), s.b.data(), s.c.data());
    runtime_local_pose(d.model, d.plan, d.model.clips[clip], s.y.data(), s.p.data(), out);
}

void RuntimeDecoder::decode_pose(std::size_t clip, std::size_t frame, double* out_row) const {
    const Impl& d = *impl_;
    d.check(clip, frame);
    RtScratch& s = rt_scratch();
    d.prepare(s);
    d.frame_y(clip, frame, s.y.data(), s.a.data(), s.b.data(), s.c.data());
    const ClipEntry& e = d.model.clips[clip];
    runtime_dofs(d.plan, e, s.y.data(), s.p.data());
    d.model.row_of(e, s.p.data(), out_row);
}

void RuntimeDecoder::decode_local_poses(std::size_t clip, std::size_t begin, std::size_t end,
                                        std::vector<LocalPose>& out) const {
    const Impl& d = *impl_;
    d.check(clip);
    if (begin > end || end > frame_count(clip))
        throw InvalidArgument("RuntimeDecoder: frames [" + std::to_string(begin) + ", " + std::to_string(end) +
                              ") outside [0, " + std::to_string(frame_count(clip)) + ")");
    out.resize(end - begin);
    std::vector<double> p(static_cast<std::size_t>(d.model.dofs));
    const ClipEntry& e = d.model.clips[clip];
    d.each_frame(clip, begin, end, [&](std::size_t f, const double* y) {
        runtime_local_pose(d.model, d.plan, e, y, p.data(), out[f - begin]);
    });
}

FrameMatrix RuntimeDecoder::decode_frames(std::size_t clip, std::size_t begin, std::size_t end) const {
    const Impl& d = *impl_;
    d.check(clip);
    if (begin > end || end > frame_count(clip))
        throw InvalidArgument("RuntimeDecoder: frames [" + std::to_string(begin) + ", " + std::to_string(end) +
                              ") outside [0, " + std::to_string(frame_count(clip)) + ")");
    const ClipEntry& e = d.model.clips[clip];
    const std::size_t channels = d.model.skeletons[e.skeleton].skeleton->channel_count();
    FrameMatrix rows(static_cast<Eigen::Index>(end - begin), static_cast<Eigen::Index>(channels));
    std::vector<double> p(static_cast<std::size_t>(d.model.dofs)), row(channels);
    d.each_frame(clip, begin, end, [&](std::size_t f, const double* y) {
        runtime_dofs(d.plan, e, y, p.data());
        d.model.row_of(e, p.data(), row.data());
        for (std::size_t k = 0; k < channels; ++k)
            rows(static_cast<Eigen::Index>(f - begin), static_cast<Eigen::Index>(k)) = row[k];
    });
    return rows;
}

Clip RuntimeDecoder::decode_clip(std::size_t clip) const {
    Clip out;
    out.skeleton = skeleton(clip);
    out.frame_rate = frame_rate();
    out.channels = decode_frames(clip, 0, frame_count(clip));
    return out;
}

}  // namespace mocapdb::packing
