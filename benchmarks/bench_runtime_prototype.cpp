// Prototype of a runtime packed format (a measurement, not a format): can a time-LOCAL transform give
// a cold random pose from the stored bytes in about a microsecond without losing format 2's bytes?
// Results and reading: benchmarks/RESULTS.md, "Runtime format prototype" and the sections after it.
// Its winner (variant 9) is now library code (packing::encode_runtime, RuntimeDecoder); the variants
// measured on the way (2, 4, 7, 8, 9), the pose kernels' A/B, the float64 product, --dof identity and
// the estimates of other codes were deleted once the library held the winner: they, and the commands
// of those sections, are in the code of 3474e3c.
//
// What is left: the first candidate's coder (variant 1) on the library's transform, beside format 2
// and the library's runtime tier.
// - The transform (lib/src/packing/runtime_transform.hpp, the library's own): per clip y = U⁻¹ x in
//   format 2's dof basis (the group's skeletons, weights and basis parsed from format 2's bytes), keys
//   every W frames (shared by neighbouring windows), and between them a closed-loop hierarchical linear
//   prediction: level j holds the frames at odd multiples of W/2^j, each predicted as the mean of its
//   two reconstructed neighbours, the difference quantized (dead zone, --rounding). Keys --key-offsets
//   step indices finer than the coarsest that holds (checked again); each window the coarsest step that
//   keeps its frames within E by the decoder's own y -> dofs -> row (x = U y in float32) and FK.
// - Variant 1's bitstream: each column's rows up to the last nonzero one coded JPEG-like ((zero run,
//   bit length) pairs as one symbol, sign and lower bits raw, an end symbol), static canonical Huffman
//   codes per (level, row/8) limited to --code-bits bits so that one table lookup decodes a symbol.
//   Per window: key step, key, window step, a directory (each internal node's left-subtree size in
//   bits, per level one width), the columns in tree order (frame t's path: skip left subtrees).
// - With --poses N: every frame of every clip is decoded from variant 1's bytes and compared with its
//   source (FK, cm), and N cold random local poses (random clip and frame, nothing kept; y -> local
//   pose by the library's pose kernels) are timed (thread CPU, best of --reps) beside format 2's
//   GroupDecoder::decode_local_pose on the same sequence. Bytes: entries + 3-byte offsets + code
//   tables (5 bits per symbol) + format 2's header (a conservative stand-in).
// - The library row, where (W, key offset) is the library's (8:4 or 16:12): encode_runtime and
//   RuntimeDecoder on the same packed groups; every frame's local pose checked equal, bit for bit, to
//   variant 1's (its y through the same pose kernels), and its cold local pose timed in the same
//   repeats.
// Also printed: the ideal static entropy of the transform's values per (level, row) context, and of
// format 2's own coefficients under the same estimator.
//
//   bench_runtime_prototype [--folders cmu-walkrun-pfnn,cmu-asfamc] [--errors 1,0.1] [--windows 16,32]
//                           [--key-offsets 0,12] [--combos 8:4,16:12] [--rounding 0.4] [--code-bits 11]
//                           [--poses N] [--limit N] [--reps 3]
#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "bench_timing.hpp"
#include "shared_folder.hpp"
#include "mocapdb/motion/forward_kinematics.hpp"
#include "mocapdb/packing/group_decoder.hpp"
#include "mocapdb/packing/packed_group.hpp"
#include "mocapdb/packing/runtime_decoder.hpp"
#include "mocapdb/packing/runtime_encoder.hpp"
#include "../lib/src/packing/group_model.hpp"
#include "../lib/src/packing/runtime_bits.hpp"
#include "../lib/src/packing/runtime_codes.hpp"
#include "../lib/src/packing/runtime_layout.hpp"
#include "../lib/src/packing/runtime_pose_plan.hpp"
#include "../lib/src/packing/runtime_transform.hpp"

using namespace mocapdb;
using namespace mocapdb::packing;
using detail::RuntimeCoefficients;
using detail::RuntimeEntry;

namespace {

/// Empirical static entropy of symbols per context, bits, with a table cost per used entry.
struct StaticCost {
    std::map<std::pair<int, int>, std::map<int, std::size_t>> counts;  // (context) -> symbol -> n
    double extra_bits = 0.0;                                           // escapes' uniform bits
    void add(int c1, int c2, std::int32_t q) {
        constexpr int kDirect = 40;
        int sym = q;
        if (q > kDirect || q < -kDirect) {
            sym = q > 0 ? kDirect + 1 : -kDirect - 1;
            extra_bits += 2.0 * detail::rt_bit_length(static_cast<std::uint64_t>(std::abs(q) - kDirect)) - 1.0;
        }
        ++counts[{c1, c2}][sym];
    }
    /// Bits of the contexts whose first key is `level` (all when level < 0), escapes excluded.
    double bits(int level = -1) const {
        double total = level < 0 ? extra_bits : 0.0;
        for (const auto& [ctx, hist] : counts) {
            if (level >= 0 && ctx.first != level) continue;
            std::size_t n = 0;
            for (const auto& [s, k] : hist) n += k;
            for (const auto& [s, k] : hist) total += static_cast<double>(k) * std::log2(static_cast<double>(n) / static_cast<double>(k));
            total += 10.0 * static_cast<double>(hist.size());
        }
        return total;
    }
};

/// The transform's values into cost (keys in context (0, row), a window's columns in (level, row));
/// returns the step bytes' bits (one per key and window); counts the nonzero detail values.
double add_static(const RuntimeCoefficients& r, StaticCost& cost, std::size_t& nonzero) {
    std::vector<int> tl, tf;
    detail::runtime_tree_order(r.window, tl, tf);
    double bits = 0.0;
    for (const RuntimeEntry& e : r.entries) {
        bits += e.step < 0 ? 8.0 : 16.0;
        for (std::size_t d = 0; d < e.key.size(); ++d) cost.add(0, static_cast<int>(d), e.key[d]);
        for (std::size_t i = 0; i < e.columns.size(); ++i)
            for (std::size_t d = 0; d < e.columns[i].size(); ++d) {
                cost.add(tl[i], static_cast<int>(d), e.columns[i][d]);
                if (e.columns[i][d]) ++nonzero;
            }
    }
    return bits;
}

/// Static estimate of format 2's own coefficients (window step as stored, rounding 0.4, no trim).
double format2_static_bits(const detail::GroupModel& m, const std::vector<const Clip*>& clips) {
    StaticCost cost;
    const auto Da = static_cast<Eigen::Index>(m.active.size());
    const int W = m.window;
    const MatX Uinv = m.dof_basis.partialPivLu().inverse();
    const MatX Vinv_t = m.time_basis.partialPivLu().inverse().transpose();
    double bits = 0.0;
    for (std::size_t i = 0; i < clips.size(); ++i) {
        const detail::ClipEntry& e = m.clips[i];
        const MatX x = m.weighted_active(*clips[i], m.skeletons[e.skeleton], e.canonical);
        const auto F = x.cols();
        const Eigen::Index nw = (F + W - 1) / W;
        for (Eigen::Index w = 0; w < nw; ++w) {
            const auto& we = m.windows[e.first_window + static_cast<std::uint64_t>(w)];
            bits += 8;
            if (we.step == detail::kRawStep) continue;
            MatX xw(Da, W);
            for (int t = 0; t < W; ++t) xw.col(t) = x.col(std::min<Eigen::Index>(w * W + t, F - 1));
            const MatX g = Uinv * xw * Vinv_t;
            const double inv = 1.0 / detail::step_of(we.step);
            for (Eigen::Index d = 0; d < Da; ++d)
                for (int k = 0; k < W; ++k) {
                    const double v = g(d, k);
                    const auto q = static_cast<std::int32_t>(std::floor(std::abs(v) * inv + 0.4));
                    cost.add(k, static_cast<int>(d), v < 0 ? -q : q);
                }
        }
    }
    return bits + cost.bits();
}

// ---- Variant 1: a real bitstream of the transform, to time a cold pose from the stored bytes ----

/// MSB-first reads over a buffer with at least 8 bytes of slack after the data.
struct BitReader {
    const std::uint8_t* data;
    std::size_t pos;  // bits
    std::uint32_t get(int bits) {
        if (bits == 0) return 0;
        const auto v = static_cast<std::uint32_t>(detail::rt_peek(data, pos) >> (64 - bits));
        pos += static_cast<std::size_t>(bits);
        return v;
    }
};

/// Symbols of a column: -1 end of column, 16 * 32 sixteen zeros, else run * 32 + the value's bit
/// length; a code's symbol s is its entry s + 1.
constexpr int kEnd = -1;
constexpr int kZeroRun = 16 * 32;
constexpr std::size_t kAlphabet = kZeroRun + 2;
struct Coded {
    int start, sym;  // context row (the run's start), symbol
    std::int32_t q;  // the value (value symbols)
};

/// Variant 1 of one group: entry byte offsets, the entries' bits, the codes.
struct RuntimeGroup {
    int W = 0, levels = 0, Da = 0, buckets = 0, B = 11;  // B: code lengths and decode lookups (--code-bits)
    struct Code {
        std::vector<std::uint8_t> length;  // per symbol entry; 0: unused
        std::vector<std::uint32_t> code;
    };
    std::vector<Code> codes;             // (level, bucket); level 0 = keys
    std::vector<std::uint32_t> offsets;  // per entry, byte offset
    std::vector<std::size_t> clip_first;
    std::vector<std::uint8_t> bytes;     // entries' bits, 8 bytes of slack at the end
    std::size_t table_bits = 0, directory_bits = 0;
    /// Every context's decode table, one after the other (2^B entries each): bits 0-3 the code length,
    /// 4-8 the zero run (16: sixteen zeros), 9-13 the value's bit length (0: none), 14 end.
    std::vector<std::uint16_t> flat;

    const Code& code(int level, int row) const { return codes[static_cast<std::size_t>(level * buckets + row / 8)]; }

    void symbols(const std::vector<std::int32_t>& v, std::vector<Coded>& out) const {
        int n = static_cast<int>(v.size());
        while (n > 0 && v[static_cast<std::size_t>(n - 1)] == 0) --n;
        int start = 0;
        for (int d = 0; d < n; ++d) {
            const std::int32_t q = v[static_cast<std::size_t>(d)];
            if (q == 0) continue;
            while (d - start >= 16) {
                out.push_back({start, kZeroRun, 0});
                start += 16;
            }
            const int c = detail::rt_bit_length(static_cast<std::uint64_t>(std::abs(q)));
            out.push_back({start, (d - start) * 32 + c, q});
            start = d + 1;
        }
        if (n < static_cast<int>(v.size())) out.push_back({start, kEnd, 0});
    }
    void write_column(detail::RtBitWriter& out, int level, const std::vector<std::int32_t>& v) const {
        std::vector<Coded> coded;
        symbols(v, coded);
        for (const Coded& c : coded) {
            const Code& k = code(level, c.start);
            const auto s = static_cast<std::size_t>(c.sym + 1);
            out.put(k.code[s], k.length[s]);
            if (c.sym == kEnd || c.sym == kZeroRun) continue;
            out.put(c.q < 0 ? 1u : 0u, 1);
            out.put(static_cast<std::uint32_t>(std::abs(c.q)), (c.sym & 31) - 1);
        }
    }
    /// y[d] = mean of a[d] and b[d] (keys: a == nullptr, 0), plus q[d] * step where q[d] is nonzero.
    void read_column(BitReader& in, int level, const double* a, const double* b, double step, double* y) const {
        if (a) {
            for (int d = 0; d < Da; ++d) y[d] = 0.5 * (a[d] + b[d]);
        } else {
            std::fill(y, y + Da, 0.0);
        }
        const std::uint16_t* table = flat.data() + (static_cast<std::size_t>(level * buckets) << B);
        detail::RtFastBits bits(in.data, in.pos);
        int d = 0;
        while (d < Da) {
            bits.refill();
            const std::uint16_t e = table[(static_cast<std::size_t>(d >> 3) << B) | static_cast<std::size_t>(bits.buf >> (64 - B))];
            if (e & (1u << 14)) {
                bits.drop(e & 15);
                break;
            }
            const int len = e & 15, cat = (e >> 9) & 31;
            d += (e >> 4) & 31;
            const auto v = static_cast<std::uint32_t>(((bits.buf << len) >> 1) >> (63 - cat));
            bits.drop(len + cat);
            if (cat) {
                const auto mag = static_cast<std::int32_t>((1u << (cat - 1)) | (v & ((1u << (cat - 1)) - 1)));
                y[d] = y[d] + ((v >> (cat - 1)) ? -mag : mag) * step;
                ++d;
            }
        }
        in.pos = bits.consumed;
    }
};

/// From the window's step byte on: the step, the directory (per level a 5-bit width, then each
/// internal node's left-subtree size in bits at that width) and the columns in tree order (levels
/// tl). Returns the directory's bits.
std::size_t write_window(const RuntimeGroup& g, detail::RtBitWriter& out, const RuntimeEntry& e, const std::vector<int>& tl) {
    const int levels = g.levels;
    out.put(static_cast<std::uint32_t>(e.step), 8);
    // Bits before each column; a level-l node's left subtree is the next 2^(levels - l) - 1 columns.
    std::vector<std::size_t> at{0};
    for (std::size_t i = 0; i < e.columns.size(); ++i) {
        detail::RtBitWriter scratch;
        g.write_column(scratch, tl[i], e.columns[i]);
        at.push_back(at.back() + scratch.bits());
    }
    std::vector<std::vector<std::size_t>> left(static_cast<std::size_t>(levels));
    for (std::size_t i = 0; i < e.columns.size(); ++i)
        if (tl[i] < levels) left[static_cast<std::size_t>(tl[i])].push_back(at[i + (std::size_t{1} << (levels - tl[i]))] - at[i + 1]);
    const std::size_t before = out.bits();
    std::vector<int> width(static_cast<std::size_t>(levels), 0);
    for (int l = 1; l < levels; ++l) {
        for (std::size_t s : left[static_cast<std::size_t>(l)])
            width[static_cast<std::size_t>(l)] = std::max(width[static_cast<std::size_t>(l)], detail::rt_bit_length(s));
        out.put(static_cast<std::uint32_t>(width[static_cast<std::size_t>(l)]), 5);
    }
    for (int l = 1; l < levels; ++l)
        for (std::size_t s : left[static_cast<std::size_t>(l)]) out.put(s, width[static_cast<std::size_t>(l)]);
    const std::size_t directory = out.bits() - before;
    for (std::size_t i = 0; i < e.columns.size(); ++i) g.write_column(out, tl[i], e.columns[i]);
    return directory;
}

RuntimeGroup build_runtime(const RuntimeCoefficients& r, int Da, int code_bits) {
    RuntimeGroup g;
    g.W = r.window;
    g.levels = r.levels;
    g.Da = Da;
    g.B = code_bits;
    g.buckets = (Da + 7) / 8;
    g.clip_first = r.clip_first;
    std::vector<int> tl, tf;
    detail::runtime_tree_order(g.W, tl, tf);
    std::vector<std::vector<std::size_t>> hist(static_cast<std::size_t>((g.levels + 1) * g.buckets), std::vector<std::size_t>(kAlphabet, 0));
    std::vector<Coded> coded;
    auto count = [&](int level, const std::vector<std::int32_t>& v) {
        coded.clear();
        g.symbols(v, coded);
        for (const Coded& c : coded) ++hist[static_cast<std::size_t>(level * g.buckets + c.start / 8)][static_cast<std::size_t>(c.sym + 1)];
    };
    for (const auto& e : r.entries) {
        count(0, e.key);
        for (std::size_t i = 0; i < e.columns.size(); ++i) count(tl[i], e.columns[i]);
    }
    const std::size_t n = std::size_t{1} << g.B;
    g.codes.resize(hist.size());
    g.flat.assign(hist.size() * n, 0);
    for (std::size_t c = 0; c < hist.size(); ++c) {
        RuntimeGroup::Code& k = g.codes[c];
        k.length = detail::rt_code_lengths(hist[c], g.B);
        k.code = detail::rt_canonical_codes(k.length);
        std::size_t used = 0;
        for (std::size_t s = 0; s < kAlphabet; ++s) {
            const int l = k.length[s];
            if (!l) continue;
            ++used;
            const int sym = static_cast<int>(s) - 1;
            const int end = sym == kEnd, zeros = sym == kZeroRun;
            const int run = end ? 0 : zeros ? 16 : sym >> 5, cat = end || zeros ? 0 : sym & 31;
            const auto packed = static_cast<std::uint16_t>(l | run << 4 | cat << 9 | end << 14);
            const std::size_t base = static_cast<std::size_t>(k.code[s]) << (g.B - l);
            for (std::size_t i = 0; i < (std::size_t{1} << (g.B - l)); ++i) g.flat[c * n + base + i] = packed;
        }
        if (used) g.table_bits += 8 + 5 * used;
    }
    detail::RtBitWriter out;
    for (const auto& e : r.entries) {
        out.align();
        g.offsets.push_back(static_cast<std::uint32_t>(out.bytes.size()));
        out.put(static_cast<std::uint32_t>(e.key_step), 8);
        g.write_column(out, 0, e.key);
        if (e.step < 0) continue;
        g.directory_bits += write_window(g, out, e, tl);
    }
    out.align();
    g.bytes = std::move(out.bytes);
    g.bytes.resize(g.bytes.size() + 8, 0);
    return g;
}

/// A window's directory at bit pos (per level a width, then the left-subtree sizes): into skip[l] the
/// size of the left subtree frame t's path skips at level l; returns the bit after the directory.
std::size_t read_directory(const std::uint8_t* data, std::size_t pos, int levels, int t, std::size_t* skip) {
    BitReader in{data, pos};
    int width[8] = {0};
    for (int l = 1; l < levels; ++l) width[l] = static_cast<int>(in.get(5));
    // Level l's sizes start after the earlier levels' (2^(l-1) each).
    std::size_t at = in.pos;
    for (int l = 1; l < levels; ++l) {
        const std::size_t node = static_cast<std::size_t>(t) >> (levels - l + 1);
        BitReader s{data, at + node * static_cast<std::size_t>(width[l])};
        skip[l] = s.get(width[l]);
        at += (std::size_t{1} << (l - 1)) * static_cast<std::size_t>(width[l]);
    }
    return at;
}

/// A frame of a clip into y (Da values), from the bytes alone; a, b, c: Da values of scratch each.
void runtime_frame(const RuntimeGroup& g, std::size_t clip, std::size_t frame, double* y, double* a, double* b, double* c) {
    const std::size_t w = frame / static_cast<std::size_t>(g.W);
    const int t = static_cast<int>(frame % static_cast<std::size_t>(g.W));
    const std::size_t entry = g.clip_first[clip] + w;
    {
        // The window's bytes and the next key's: one pass of prefetches before the first decode, so
        // that the misses overlap instead of following one another.
        const std::size_t end = std::min<std::size_t>(g.bytes.size(), std::size_t{g.offsets[entry + 1]} + 192);
        for (std::size_t at = g.offsets[entry] & ~std::size_t{63}; at < end; at += 64) __builtin_prefetch(g.bytes.data() + at);
    }
    BitReader in{g.bytes.data(), std::size_t{g.offsets[entry]} * 8};
    const double key_step = detail::step_of(static_cast<int>(in.get(8)));
    if (t == 0) {
        g.read_column(in, 0, nullptr, nullptr, key_step, y);
        return;
    }
    g.read_column(in, 0, nullptr, nullptr, key_step, a);
    {
        BitReader next{g.bytes.data(), std::size_t{g.offsets[entry + 1]} * 8};
        const double next_step = detail::step_of(static_cast<int>(next.get(8)));
        g.read_column(next, 0, nullptr, nullptr, next_step, b);
    }
    const double step = detail::step_of(static_cast<int>(in.get(8)));
    std::size_t skip[8] = {0};
    in.pos = read_directory(g.bytes.data(), in.pos, g.levels, t, skip);
    int lo = 0, hi = g.W;
    double* lo_y = a;
    double* hi_y = b;
    for (int l = 1;; ++l) {
        const int mid = (lo + hi) / 2;
        if (mid == t) {
            g.read_column(in, l, lo_y, hi_y, step, y);
            return;
        }
        double* out = lo_y != a && hi_y != a ? a : lo_y != b && hi_y != b ? b : c;
        g.read_column(in, l, lo_y, hi_y, step, out);
        if (t < mid) {
            hi = mid;
            hi_y = out;
        } else {
            in.pos += skip[l];
            lo = mid;
            lo_y = out;
        }
    }
}

bool same_pose(const LocalPose& a, const LocalPose& b) {
    return a.rotations.size() == b.rotations.size() &&
           std::memcmp(a.rotations.data(), b.rotations.data(), a.rotations.size() * sizeof(Quat)) == 0 &&
           std::memcmp(a.translations.data(), b.translations.data(), a.translations.size() * sizeof(Vec3)) == 0;
}

}  // namespace

int main(int argc, char** argv) {
    std::vector<std::string> folders{"cmu-walkrun-pfnn", "cmu-asfamc"};
    std::vector<double> errors{1.0, 0.1};
    std::vector<int> windows{16, 32};
    std::vector<int> key_offsets{0, 12};
    std::vector<std::pair<int, int>> combos;  // --combos 16:12,8:4: (W, key offset) pairs instead of every W with every offset
    double rounding = 0.4;
    int code_bits = 11;
    std::size_t limit = 0;
    std::size_t poses = 0;  // > 0: build the bitstream, verify every frame, time this many cold poses
    int reps = 3;           // repeats of the timings (best of)
    for (int a = 1; a < argc; a += 2) {
        const std::string k = argv[a], v = a + 1 < argc ? argv[a + 1] : "";
        if (k == "--folders") folders = bench::split_list(v);
        else if (k == "--errors") errors = bench::parse_doubles(v);
        else if (k == "--windows") { windows.clear(); for (auto& s : bench::split_list(v)) windows.push_back(std::stoi(s)); }
        else if (k == "--key-offsets") { key_offsets.clear(); for (auto& s : bench::split_list(v)) key_offsets.push_back(std::stoi(s)); }
        else if (k == "--combos") {
            for (auto& x : bench::split_list(v)) combos.push_back({std::stoi(x.substr(0, x.find(':'))), std::stoi(x.substr(x.find(':') + 1))});
        }
        else if (k == "--rounding") rounding = std::stod(v);
        else if (k == "--code-bits") code_bits = std::stoi(v);
        else if (k == "--limit") limit = std::stoul(v);
        else if (k == "--poses") poses = std::stoul(v);
        else if (k == "--reps") reps = std::stoi(v);
        else {
            std::fprintf(stderr, "bench_runtime_prototype: unknown option %s (the options of the deleted variants, such as --quads, "
                                 "--lookups and --float-dofs, are in the code of 3474e3c)\n", k.c_str());
            return 2;
        }
    }
    if (code_bits < 1 || code_bits > 15) {
        std::fprintf(stderr, "bench_runtime_prototype: --code-bits %d, expected 1 to 15\n", code_bits);
        return 2;
    }
    std::printf("folder,E,format2_bytes,format2_payload,format2_static,W,key_offset,hier_static,hier_max,windows,keys,nonzero,seconds\n");
    for (const auto& folder : folders) {
        const std::vector<Clip> clips = bench::read_shared_folder(folder, limit);
        std::vector<const Clip*> all;
        for (const Clip& c : clips) all.push_back(&c);
        const auto groups = group_clips(all);
        for (double E : errors) {
            PackOptions o;
            o.format = PackFormat::Archive;  // the format-3 group the runtime body goes beside
            o.max_error_cm = E;
            o.time_basis = TimeBasis::Learned;
            o.dof_basis = DofBasis::Learned;
            std::vector<detail::GroupModel> models(groups.size());
            // Per group the pose kernels' plan: portable for the transform's check (as encode_runtime),
            // AVX2 where the CPU has it for the decodes (the same bits).
            std::vector<detail::RuntimePosePlan> check_plans(groups.size()), plans(groups.size());
            std::vector<std::vector<const Clip*>> members(groups.size());
            std::size_t f2_bytes = 0, f2_payload = 0, f2_header = 0;
            std::vector<std::vector<std::uint8_t>> f2(groups.size());
            double f2_static = 0.0;
            for (std::size_t g = 0; g < groups.size(); ++g) {
                for (std::size_t i : groups[g]) members[g].push_back(all[i]);
                const PackedGroup pg = pack_group(members[g], o);
                f2_bytes += pg.stats.bytes;
                f2_payload += pg.stats.payload_bytes + pg.stats.table_bytes;
                f2_header += pg.stats.header_bytes;
                f2[g] = pg.bytes;
                models[g].read_header(pg.bytes.data(), pg.bytes.size());
                detail::make_runtime_pose_plan(models[g], false, check_plans[g]);
                detail::make_runtime_pose_plan(models[g], true, plans[g]);
                f2_static += format2_static_bits(models[g], members[g]);
            }
            std::vector<std::pair<int, int>> runs = combos;  // (W, key offset)
            if (runs.empty())
                for (int W : windows)
                    for (int ko : key_offsets) runs.push_back({W, ko});
            for (const auto& [W, ko] : runs) {
                const auto t0 = bench::Clock::now();
                double static_bits = 0.0, max_error = 0.0;
                std::vector<double> by_level(10, 0.0);
                std::size_t windows_total = 0, keys = 0, nonzero = 0;
                std::vector<RuntimeCoefficients> coefficients;
                for (std::size_t g = 0; g < groups.size(); ++g) {
                    coefficients.push_back(detail::runtime_transform(models[g], check_plans[g], members[g], E, W, ko, rounding));
                    const RuntimeCoefficients& r = coefficients.back();
                    StaticCost cost;
                    static_bits += add_static(r, cost, nonzero);
                    static_bits += cost.bits();
                    for (std::size_t j = 0; j < by_level.size(); ++j) by_level[j] += cost.bits(static_cast<int>(j)) / 8;
                    max_error = std::max(max_error, r.max_error_cm);
                    keys += r.entries.size();
                    for (const RuntimeEntry& e : r.entries) windows_total += e.step >= 0 ? 1 : 0;
                }
                std::printf("%s,%g,%zu,%zu,%.0f,%d,%d,%.0f,%.7f,%zu,%zu,%zu,%.1f\n", folder.c_str(), E, f2_bytes, f2_payload, f2_static / 8, W,
                            ko, static_bits / 8, max_error, windows_total, keys, nonzero, bench::seconds_since(t0));
                if (poses > 0) {
                    // Variant 1's bytes: entries, a 3-byte offset per entry, the code tables, format 2's header
                    // as a stand-in for the shared header (skeletons, dof basis, constants, clip table).
                    std::vector<RuntimeGroup> runtime;
                    double bits = 0.0, directory = 0.0, tables = 0.0;
                    std::size_t entries = 0;
                    for (std::size_t g = 0; g < groups.size(); ++g) {
                        runtime.push_back(build_runtime(coefficients[g], static_cast<int>(models[g].active.size()), code_bits));
                        const RuntimeGroup& rg = runtime.back();
                        bits += 8.0 * static_cast<double>(rg.bytes.size() - 8);
                        directory += static_cast<double>(rg.directory_bits);
                        tables += static_cast<double>(rg.table_bits);
                        entries += rg.offsets.size();
                    }
                    const double bytes = bits / 8 + 3.0 * static_cast<double>(entries) + tables / 8 + static_cast<double>(f2_header);
                    // Every frame decoded from the bytes, FK against the source clip.
                    double worst = 0.0;
                    GlobalPose pose;
                    for (std::size_t g = 0; g < groups.size(); ++g) {
                        const auto& m = models[g];
                        const auto Da = m.active.size();
                        std::vector<double> y(Da), a(Da), b(Da), c(Da), p(static_cast<std::size_t>(m.dofs)), row;
                        for (std::size_t i = 0; i < members[g].size(); ++i) {
                            const Clip& clip = *members[g][i];
                            const auto& e = m.clips[i];
                            const Skeleton& sk = *m.skeletons[e.skeleton].skeleton;
                            row.resize(sk.channel_count());
                            const MatX source = joint_positions(clip);
                            for (std::size_t f = 0; f < clip.frame_count(); ++f) {
                                runtime_frame(runtime[g], i, f, y.data(), a.data(), b.data(), c.data());
                                detail::runtime_dofs(plans[g], e, y.data(), p.data());
                                m.row_of(e, p.data(), row.data());
                                forward_kinematics(sk, row.data(), pose);
                                for (std::size_t j = 0; j < sk.size(); ++j)
                                    worst = std::max(worst, (pose.positions[j] - source.block<3, 1>(3 * static_cast<Eigen::Index>(j),
                                                                                                      static_cast<Eigen::Index>(f))).norm());
                            }
                        }
                    }
                    // Cold random local poses: the same sequence for every decoder.
                    std::mt19937_64 rng(7);
                    std::vector<std::array<std::size_t, 3>> seq;
                    std::size_t frames_total = 0;
                    for (const auto& mem : members)
                        for (const Clip* c : mem) frames_total += c->frame_count();
                    for (std::size_t n = 0; n < poses; ++n) {
                        std::size_t u = std::uniform_int_distribution<std::size_t>(0, frames_total - 1)(rng);
                        for (std::size_t g = 0; g < members.size(); ++g)
                            for (std::size_t i = 0; i < members[g].size(); ++i) {
                                const std::size_t fc = members[g][i]->frame_count();
                                if (u < fc) {
                                    seq.push_back({g, i, u});
                                    u = ~std::size_t{0} >> 1;
                                    g = members.size() - 1;
                                    break;
                                }
                                u -= fc;
                            }
                    }
                    std::vector<GroupDecoder> decoders;
                    for (const auto& bytes_g : f2) decoders.emplace_back(bytes_g);
                    LocalPose out;
                    std::vector<std::vector<double>> scratch(groups.size());
                    for (std::size_t g = 0; g < groups.size(); ++g)
                        scratch[g].assign(4 * models[g].active.size() + static_cast<std::size_t>(models[g].dofs), 0.0);
                    // The library's runtime tier (packing::encode_runtime, RuntimeDecoder) on the same packed
                    // groups at this W (its key offset: W 8 -> 4, W 16 -> 12): its bytes (bodies + the same
                    // header stand-in), every frame's local pose against variant 1's, its cold local pose.
                    const bool library_tier = (W == 8 && ko == 4) || (W == 16 && ko == 12);
                    std::vector<RuntimeBody> lib_bodies;
                    std::vector<RuntimeDecoder> lib_decoders;
                    double lib_bytes = static_cast<double>(f2_header);
                    std::size_t lib_resident = 0, lib_differ = 0, lib_frames = 0;
                    if (library_tier) {
                        for (std::size_t g = 0; g < groups.size(); ++g) {
                            RuntimeOptions ro;
                            ro.max_error_cm = E;
                            ro.window = W;
                            ro.rounding = rounding;
                            lib_bodies.push_back(encode_runtime(f2[g], members[g], ro));
                            lib_bytes += static_cast<double>(lib_bodies.back().bytes.size());
                        }
                        for (std::size_t g = 0; g < groups.size(); ++g) {
                            lib_decoders.emplace_back(f2[g].data(), f2[g].size(), lib_bodies[g].bytes.data(), lib_bodies[g].bytes.size());
                            lib_resident += lib_decoders.back().resident_bytes();
                        }
                        LocalPose ref, got;
                        for (std::size_t g = 0; g < groups.size(); ++g) {
                            const auto& m = models[g];
                            const std::size_t Da = m.active.size();
                            double* base = scratch[g].data();
                            for (std::size_t i = 0; i < members[g].size(); ++i)
                                for (std::size_t f = 0; f < members[g][i]->frame_count(); ++f, ++lib_frames) {
                                    runtime_frame(runtime[g], i, f, base, base + Da, base + 2 * Da, base + 3 * Da);
                                    detail::runtime_local_pose(m, plans[g], m.clips[i], base, base + 4 * Da, ref);
                                    lib_decoders[g].decode_local_pose(i, f, got);
                                    if (!same_pose(ref, got)) ++lib_differ;
                                }
                        }
                    }
                    // Cold local pose (variant 1, format 2, the library in the same repeats), variant 1's y
                    // alone, y -> local pose alone (on each group's last y), and hot y (32 poses over and over:
                    // bytes, tables and branches learnt).
                    double ours = 1e300, theirs = 1e300, lib_cold = 1e300, decode_only = 1e300, pose_only = 1e300, hot = 1e300;
                    auto per_pose = [&](double c0) { return (bench::thread_cpu_seconds() - c0) / static_cast<double>(seq.size()) * 1e6; };
                    for (int rep = 0; rep < reps; ++rep) {
                        double c0 = bench::thread_cpu_seconds();
                        for (const auto& [g, i, f] : seq) {
                            const auto& m = models[g];
                            const std::size_t Da = m.active.size();
                            double* base = scratch[g].data();
                            runtime_frame(runtime[g], i, f, base, base + Da, base + 2 * Da, base + 3 * Da);
                            detail::runtime_local_pose(m, plans[g], m.clips[i], base, base + 4 * Da, out);
                        }
                        ours = std::min(ours, per_pose(c0));
                        c0 = bench::thread_cpu_seconds();
                        for (const auto& [g, i, f] : seq) decoders[g].decode_local_pose(i, f, out);
                        theirs = std::min(theirs, per_pose(c0));
                        if (library_tier) {
                            c0 = bench::thread_cpu_seconds();
                            for (const auto& [g, i, f] : seq) lib_decoders[g].decode_local_pose(i, f, out);
                            lib_cold = std::min(lib_cold, per_pose(c0));
                        }
                        c0 = bench::thread_cpu_seconds();
                        for (const auto& [g, i, f] : seq) {
                            const std::size_t Da = models[g].active.size();
                            double* base = scratch[g].data();
                            runtime_frame(runtime[g], i, f, base, base + Da, base + 2 * Da, base + 3 * Da);
                        }
                        decode_only = std::min(decode_only, per_pose(c0));
                        c0 = bench::thread_cpu_seconds();
                        for (const auto& [g, i, f] : seq) {
                            const auto& m = models[g];
                            double* base = scratch[g].data();
                            detail::runtime_local_pose(m, plans[g], m.clips[i], base, base + 4 * m.active.size(), out);
                        }
                        pose_only = std::min(pose_only, per_pose(c0));
                        c0 = bench::thread_cpu_seconds();
                        for (int again = 0; again < 200; ++again)
                            for (std::size_t n = 0; n < 32 && n < seq.size(); ++n) {
                                const auto& [g, i, f] = seq[n];
                                const std::size_t Da = models[g].active.size();
                                double* base = scratch[g].data();
                                runtime_frame(runtime[g], i, f, base, base + Da, base + 2 * Da, base + 3 * Da);
                            }
                        hot = std::min(hot, (bench::thread_cpu_seconds() - c0) / (200.0 * static_cast<double>(std::min<std::size_t>(32, seq.size()))) * 1e6);
                    }
                    std::printf("#  stages (%s kernels): y from bytes %.3f us (hot, 32 poses repeated: %.3f us), y -> local pose %.3f us\n",
                                plans.front().avx2 ? "AVX2" : "portable", decode_only, hot, pose_only);
                    if (library_tier)
                        std::printf("#  library RuntimeDecoder (W %d, %s kernels): bytes %.0f, resident %zu; %zu of %zu frames' local poses differ from "
                                    "variant 1's; cold local pose %.3f us (variant 1: %.3f us, the same repeats)\n",
                                    W, lib_decoders.front().uses_avx2() ? "AVX2" : "portable", lib_bytes, lib_resident, lib_differ, lib_frames,
                                    lib_cold, ours);
                    std::printf("#  RUNTIME bytes %.0f (entries %.0f, directory %.0f, offsets %zu, tables %.0f, header %zu); "
                                "max %.7f cm over every frame; cold local pose %.3f us (format 2: %.3f us)\n",
                                bytes, bits / 8, directory / 8, 3 * entries, tables / 8, f2_header, worst, ours, theirs);
                }
                std::printf("#  static bytes by level (0 = keys):");
                for (double b : by_level)
                    if (b > 0) std::printf(" %.0f", b);
                std::printf("\n");
                std::fflush(stdout);
            }
        }
    }
    return 0;
}
