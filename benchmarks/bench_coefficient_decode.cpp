// Prototype for issue 14 acceptance 4 (cold random pose): how fast can one window's quantized
// coefficients be entropy-decoded, and at what cost in bytes? Measured on the packed groups that
// bench_pose_access caches (--cache DIR, files FOLDER_E<E>.mdbp; run bench_pose_access first). The
// format-2 coefficients of every coded window are range-decoded once (the reference), then timed
// on one thread (thread CPU time, best of --repeats):
//   range      format 2's adaptive binary range decoder (decode_coefficients), µs per window, in
//              window order
//   cold pose  format 2's cold decode_local_pose stage by stage at 20 000 random windows (random
//              frame): range decode, dequantize (of the nonzero coefficients, as GroupDecoder does;
//              beside it of the whole grid, as before this branch), the frame's dofs (two products),
//              the local pose; each stage is the difference of two timed loops (noisy: +-0.5 µs)
//   rans S/K   a static multi-symbol code: each scan position's coefficient is one symbol (q in
//              -15..15, two escapes for larger magnitudes followed by uniform bits), coded with rANS
//              (32-bit state, 16-bit words, 2^11 probability scale, branch-free renormalization) over
//              frequency tables trained on the group, K interleaved states, context S:
//                 class   the position's class only (known before decoding: the states decode
//                         independently)
//                 shift   the class moved by a per-window offset in -4..3 (3 bits per window, chosen
//                         by the encoder for the fewest bits; tables retrained on the choice twice)
//                 nbr     class x min(upper + left neighbour levels, 2) x previous nonzero (format 2's
//                         zero-flag context, coarsened); nbr+shift both
//              payload bytes = the streams with their state flushes (4 bytes per state) and the length
//              (12 uniform bits); table bytes = an estimate of storing the tables (per context a
//              33-bit used mask and 12 bits per used symbol); decode µs per window in window order
//              and at the random windows of the cold rows.
// Every rANS decode is checked equal to the range decoder's coefficients (MISMATCH otherwise). Not a
// format: a measurement before deciding on one (RESULTS.md, "Pose access, cold decode prototype").
// Reads the packing module's internal header (group_model.hpp) for the group's scan, classes and
// window table; a prototype, not an API user.
//
//   bench_coefficient_decode --cache DIR [--folders cmu-asfamc,cmu-walkrun-pfnn] [--errors 1,0.5,0.1]
//                            [--repeats 3]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include <random>

#include "bench_timing.hpp"
#include "mocapdb/packing/group_decoder.hpp"
#include "../lib/src/packing/group_model.hpp"

using namespace mocapdb;
using namespace mocapdb::bench;
using namespace mocapdb::packing;

namespace {

constexpr int kScaleBits = 11;
constexpr std::uint32_t kScale = 1u << kScaleBits;
constexpr std::uint32_t kLow = 1u << 16;  // state kept in [2^16, 2^32): at most one 16-bit word per symbol
constexpr int kDirect = 15;               // |q| <= kDirect coded as itself
constexpr int kSymbols = 2 * kDirect + 3;  // -15..15, escape +, escape -
constexpr int kEscapePlus = 2 * kDirect + 1;
constexpr int kEscapeMinus = 2 * kDirect + 2;

struct Window {
    int step = 0;
    std::uint32_t length = 0;      // scan positions up to the last nonzero
    std::vector<std::int32_t> q;   // scan order, `length` entries
    std::size_t range_bytes = 0;
};

struct Group {
    detail::GroupModel model;
    std::size_t payload = 0;
    std::vector<std::uint8_t> bytes;
    std::vector<detail::WindowEntry> entries;  // coded windows only
    std::vector<Window> windows;
    std::vector<std::vector<std::uint8_t>> classes;  // per step
    std::vector<std::vector<std::uint8_t>> shifted;  // per step * 8 + offset + 4: classes + offset, clamped
    std::size_t positions = 0;                       // Da * W
    std::vector<std::size_t> clip_of;                // per coded window
    std::vector<std::size_t> random_order;           // coded window indices, random, 20 000
};

int symbol_of(std::int32_t q) {
    if (q > kDirect) return kEscapePlus;
    if (q < -kDirect) return kEscapeMinus;
    return q + kDirect;
}

// A context's static distribution: frequencies (sum kScale), cumulative, and slot -> symbol.
struct Table {
    std::uint32_t freq[kSymbols] = {};
    std::uint32_t cum[kSymbols] = {};
    std::uint16_t fc[kSymbols][2] = {};  // decoder's copy: frequency, cumulative
    std::uint8_t slots[kScale] = {};
};

Table make_table(const std::vector<std::uint64_t>& counts) {
    Table t;
    std::uint64_t total = 0;
    for (std::uint64_t c : counts) total += c;
    if (total == 0) {
        t.freq[kDirect] = kScale;  // never used: all mass on 0
    } else {
        // proportional, every seen symbol >= 1, then fix the sum on the largest
        std::int64_t sum = 0;
        int largest = 0;
        for (int s = 0; s < kSymbols; ++s) {
            const std::uint64_t c = counts[static_cast<std::size_t>(s)];
            if (c == 0) continue;
            auto f = static_cast<std::uint32_t>(std::llround(static_cast<double>(c) * kScale / static_cast<double>(total)));
            t.freq[s] = std::max<std::uint32_t>(1, f);
            sum += t.freq[s];
            if (c > counts[static_cast<std::size_t>(largest)]) largest = s;
        }
        t.freq[largest] = static_cast<std::uint32_t>(static_cast<std::int64_t>(t.freq[largest]) + (kScale - sum));
    }
    std::uint32_t c = 0;
    for (int s = 0; s < kSymbols; ++s) {
        t.cum[s] = c;
        t.fc[s][0] = static_cast<std::uint16_t>(t.freq[s]);
        t.fc[s][1] = static_cast<std::uint16_t>(c);
        for (std::uint32_t k = 0; k < t.freq[s]; ++k) t.slots[c + k] = static_cast<std::uint8_t>(s);
        c += t.freq[s];
    }
    return t;
}

// rANS writer with 16-bit words: symbols are pushed in reverse decode order.
struct RansWriter {
    std::vector<std::uint16_t> rev;  // words in reverse
    void put(std::uint32_t& x, std::uint32_t cum, std::uint32_t freq) {
        const std::uint64_t x_max = (std::uint64_t(kLow >> kScaleBits) << 16) * freq;
        if (x >= x_max) {
            rev.push_back(static_cast<std::uint16_t>(x & 0xFFFF));
            x >>= 16;
        }
        x = ((x / freq) << kScaleBits) + (x % freq) + cum;
    }
    void flush(std::uint32_t x) {
        rev.push_back(static_cast<std::uint16_t>(x & 0xFFFF));
        rev.push_back(static_cast<std::uint16_t>(x >> 16));
    }
};

// The decode-order symbol list of a window: (context or -1 for uniform, value, bits of a uniform).
struct Op {
    int table;  // -1: uniform `bits` bits
    std::uint32_t value;
    int bits;
    int state;  // position i codes with state i % K, its escape bits too; the length with state 0
};

constexpr int kContextNbr = 3 * 2;  // min(n, 2) x previous nonzero

template <bool kNeighbours>
int context_of(int cls, int n, int previous) {
    if constexpr (kNeighbours) return cls * kContextNbr + std::min(n, 2) * 2 + previous;
    else return cls;
}

template <int kStates, bool kNeighbours, bool kOffset>
void ops_of(const Group& g, const Window& w, int offset, std::vector<Op>& ops, std::vector<std::uint8_t>& level) {
    ops.clear();
    ops.push_back({-1, w.length >> 6, 6, 0});
    ops.push_back({-1, w.length & 63u, 6, 0});
    if constexpr (kOffset) ops.push_back({-1, static_cast<std::uint32_t>(offset + 4), 3, 0});
    const auto& classes = g.shifted[static_cast<std::size_t>(w.step * 8 + offset + 4)];
    const std::uint32_t* scan = g.model.scan.data();
    const auto rows = static_cast<std::uint32_t>(g.model.grid().rows);
    std::fill(level.begin(), level.end(), std::uint8_t(0));
    int previous = 1;
    for (std::uint32_t i = 0; i < w.length; ++i) {
        const std::uint32_t pos = scan[i];
        int n = 0;
        if constexpr (kNeighbours) n = (pos % rows > 0 ? level[pos - 1] : 0) + (pos >= rows ? level[pos - rows] : 0);
        const std::int32_t q = w.q[i];
        const int s = symbol_of(q);
        const int state = static_cast<int>(i % kStates);
        ops.push_back({context_of<kNeighbours>(classes[i], n, previous), static_cast<std::uint32_t>(s), 0, state});
        if (s >= kEscapePlus) {
            const auto v = static_cast<std::uint32_t>(std::abs(q) - kDirect);  // >= 1
            int b = 0;
            while ((v >> (b + 1)) != 0) ++b;
            ops.push_back({-1, static_cast<std::uint32_t>(b), 5, state});
            for (int top = b; top > 0; top -= 11) {  // the b low bits of v, 11 at a time from the top
                const int bits = std::min(top, 11);
                ops.push_back({-1, (v >> (top - bits)) & ((1u << bits) - 1u), bits, state});
            }
        }
        level[pos] = static_cast<std::uint8_t>(std::min(std::abs(q), 2));
        previous = q != 0;
    }
}

template <int kStates>
std::vector<std::uint8_t> encode(const std::vector<Op>& ops, const std::vector<Table>& tables) {
    RansWriter wr;
    std::uint32_t x[kStates];
    for (auto& v : x) v = kLow;
    for (std::size_t k = ops.size(); k-- > 0;) {
        const Op& op = ops[k];
        std::uint32_t& st = x[op.state];
        if (op.table < 0) {
            // uniform: frequency kScale >> bits (1 <= bits <= 11)
            wr.put(st, op.value << (kScaleBits - op.bits), kScale >> op.bits);
        } else {
            const Table& t = tables[static_cast<std::size_t>(op.table)];
            wr.put(st, t.cum[op.value], t.freq[op.value]);
        }
    }
    for (int s = kStates; s-- > 0;) wr.flush(x[s]);
    std::vector<std::uint8_t> out;
    for (std::size_t k = wr.rev.size(); k-- > 0;) {
        out.push_back(static_cast<std::uint8_t>(wr.rev[k] & 0xFF));
        out.push_back(static_cast<std::uint8_t>(wr.rev[k] >> 8));
    }
    return out;
}

// Decoder: position i decodes with state i % kStates (held in registers, the loop unrolled by
// kStates), escapes read their bits from the same state.
template <int kStates, bool kNeighbours, bool kOffset>
void decode(const std::uint8_t* data, const Group& g, int step, const std::vector<Table>& tables, std::int32_t* q,
            std::uint8_t* level) {
    const std::uint8_t* p = data;
    auto word = [](const std::uint8_t* b) { return static_cast<std::uint32_t>(b[0]) | static_cast<std::uint32_t>(b[1]) << 8; };
    std::uint32_t x[kStates];
    for (int s = 0; s < kStates; ++s) {
        x[s] = word(p) << 16 | word(p + 2);
        p += 4;
    }
    // branch-free renormalization: at most one word per symbol
    auto renorm = [&](std::uint32_t& st) {
        const bool r = st < kLow;
        const std::uint32_t w = word(p);
        st = r ? (st << 16) | w : st;
        p += r ? 2 : 0;
    };
    auto uniform = [&](std::uint32_t& st, int bits) {
        const std::uint32_t slot = st & (kScale - 1);
        const std::uint32_t v = slot >> (kScaleBits - bits);
        st = (kScale >> bits) * (st >> kScaleBits) + (slot & ((kScale >> bits) - 1));
        renorm(st);
        return v;
    };
    std::uint32_t length = uniform(x[0], 6) << 6;
    length |= uniform(x[0], 6);
    length = std::min<std::uint32_t>(length, static_cast<std::uint32_t>(g.positions));
    int offset = 0;
    if constexpr (kOffset) offset = static_cast<int>(uniform(x[0], 3)) - 4;
    const std::uint8_t* classes = g.shifted[static_cast<std::size_t>(step * 8 + offset + 4)].data();
    const std::uint32_t* scan = g.model.scan.data();
    const auto rows = static_cast<std::uint32_t>(g.model.grid().rows);
    if constexpr (kNeighbours) std::memset(level, 0, g.positions);
    int previous = 1;
    auto one = [&](std::uint32_t& st, std::uint32_t i) {
        int ctx;
        std::uint32_t pos = 0;
        if constexpr (kNeighbours) {
            pos = scan[i];
            const int n = (pos % rows > 0 ? level[pos - 1] : 0) + (pos >= rows ? level[pos - rows] : 0);
            ctx = context_of<true>(classes[i], n, previous);
        } else {
            ctx = classes[i];
        }
        const Table& t = tables[static_cast<std::size_t>(ctx)];
        const std::uint32_t slot = st & (kScale - 1);
        const int s = t.slots[slot];
        st = t.fc[s][0] * (st >> kScaleBits) + slot - t.fc[s][1];
        renorm(st);
        std::int32_t v = s - kDirect;
        if (s >= kEscapePlus) {
            const auto b = static_cast<int>(uniform(st, 5));
            std::uint32_t m = 1u << b;
            for (int top = b; top > 0; top -= 11) {
                const int bits = std::min(top, 11);
                m |= uniform(st, bits) << (top - bits);
            }
            v = static_cast<std::int32_t>(m) + kDirect;
            if (s == kEscapeMinus) v = -v;
        }
        q[i] = v;
        if constexpr (kNeighbours) {
            level[pos] = static_cast<std::uint8_t>(std::min(std::abs(v), 2));
            previous = v != 0;
        }
    };
    std::uint32_t i = 0;
    if constexpr (kStates == 1) {
        std::uint32_t a = x[0];
        for (; i < length; ++i) one(a, i);
    } else if constexpr (kStates == 2) {
        std::uint32_t a = x[0], b = x[1];
        for (; i + 2 <= length; i += 2) {
            one(a, i);
            one(b, i + 1);
        }
        if (i < length) one(a, i++);
    } else {
        static_assert(kStates == 4);
        std::uint32_t a = x[0], b = x[1], c = x[2], d = x[3];
        for (; i + 4 <= length; i += 4) {
            one(a, i);
            one(b, i + 1);
            one(c, i + 2);
            one(d, i + 3);
        }
        if (i < length) one(a, i++);
        if (i < length) one(b, i++);
        if (i < length) one(c, i++);
    }
    std::memset(q + length, 0, (g.positions - length) * sizeof(std::int32_t));
}

std::vector<std::uint8_t> read_file(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error("cannot read " + path);
    return std::vector<std::uint8_t>((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

Group load(const std::string& path) {
    Group g;
    g.bytes = read_file(path);
    g.payload = g.model.read_header(g.bytes.data(), g.bytes.size());
    g.positions = g.model.scan.size();
    g.classes.resize(detail::kMaxStep + 1);
    std::vector<std::uint8_t> level(g.positions);
    for (const detail::WindowEntry& e : g.model.windows) {
        if (e.step == detail::kRawStep) continue;
        auto& cls = g.classes[e.step];
        if (cls.empty()) {
            position_classes(g.model.levels, detail::step_of(e.step), cls);
            g.shifted.resize(g.classes.size() * 8);
            for (int o = -4; o < 4; ++o) {
                auto& sh = g.shifted[static_cast<std::size_t>(e.step * 8 + o + 4)];
                for (std::uint8_t c : cls) sh.push_back(static_cast<std::uint8_t>(std::clamp(c + o, 0, kClasses - 1)));
            }
        }
        Window w;
        w.step = e.step;
        w.range_bytes = e.size;
        w.q.resize(g.positions);
        ContextSet ctx = g.model.contexts;
        decode_coefficients(g.bytes.data() + g.payload + e.offset, e.size, cls.data(), cls.size(), g.model.grid(), ctx,
                            w.q.data(), level.data());
        for (std::size_t i = g.positions; i-- > 0;)
            if (w.q[i] != 0) {
                w.length = static_cast<std::uint32_t>(i + 1);
                break;
            }
        w.q.resize(w.length);
        g.entries.push_back(e);
        g.windows.push_back(std::move(w));
        const auto index = static_cast<std::uint64_t>(&e - g.model.windows.data());
        std::size_t c = 0;
        while (c + 1 < g.model.clips.size() && g.model.clips[c + 1].first_window <= index) ++c;
        g.clip_of.push_back(c);
    }
    std::mt19937_64 rng(7);
    std::uniform_int_distribution<std::size_t> pick(0, g.windows.size() - 1);
    for (int k = 0; k < 20000; ++k) g.random_order.push_back(pick(rng));
    return g;
}

template <int kStates, bool kNeighbours, bool kOffset>
void run_rans(const Group& g, int repeats, const char* label, double range_us, std::size_t range_bytes) {
    const int contexts = kNeighbours ? kClasses * kContextNbr : kClasses;
    std::vector<Op> ops;
    std::vector<std::uint8_t> level(g.positions);
    std::vector<int> offsets(g.windows.size(), 0);
    std::vector<Table> tables;
    double table_bits = 0;
    // kOffset: train with offset 0, pick each window's offset by its cost under those tables, train
    // again, pick again, train a last time on the final choice (so every coded symbol has a frequency).
    for (int pass = 0; pass < (kOffset ? 3 : 1); ++pass) {
        std::vector<std::vector<std::uint64_t>> counts(static_cast<std::size_t>(contexts),
                                                       std::vector<std::uint64_t>(kSymbols, 0));
        for (std::size_t k = 0; k < g.windows.size(); ++k) {
            ops_of<kStates, kNeighbours, kOffset>(g, g.windows[k], offsets[k], ops, level);
            for (const Op& op : ops)
                if (op.table >= 0) ++counts[static_cast<std::size_t>(op.table)][op.value];
        }
        tables.clear();
        table_bits = 0;
        for (const auto& c : counts) {
            tables.push_back(make_table(c));
            table_bits += kSymbols;
            for (std::uint64_t v : c) table_bits += v != 0 ? 12 : 0;
        }
        if (pass == 2 || !kOffset) break;
        for (std::size_t k = 0; k < g.windows.size(); ++k) {
            double best_bits = 1e300;
            for (int o = -4; o < 4; ++o) {
                ops_of<kStates, kNeighbours, kOffset>(g, g.windows[k], o, ops, level);
                double bits = 0;
                for (const Op& op : ops) {
                    if (op.table < 0) continue;
                    const std::uint32_t f = tables[static_cast<std::size_t>(op.table)].freq[op.value];
                    bits += f == 0 ? 40.0 : kScaleBits - std::log2(static_cast<double>(f));
                }
                if (bits < best_bits) {
                    best_bits = bits;
                    offsets[k] = o;
                }
            }
        }
    }
    std::vector<std::vector<std::uint8_t>> streams;
    std::size_t bytes = 0;
    for (std::size_t k = 0; k < g.windows.size(); ++k) {
        ops_of<kStates, kNeighbours, kOffset>(g, g.windows[k], offsets[k], ops, level);
        streams.push_back(encode<kStates>(ops, tables));
        bytes += streams.back().size();
    }
    // check
    std::vector<std::int32_t> q(g.positions);
    for (std::size_t k = 0; k < g.windows.size(); ++k) {
        decode<kStates, kNeighbours, kOffset>(streams[k].data(), g, g.windows[k].step, tables, q.data(), level.data());
        const Window& w = g.windows[k];
        for (std::size_t i = 0; i < g.positions; ++i)
            if (q[i] != (i < w.length ? w.q[i] : 0)) {
                std::printf("MISMATCH %s window %zu position %zu\n", label, k, i);
                return;
            }
    }
    double best_s = 1e300;
    for (int r = 0; r < repeats; ++r) {
        const double t0 = thread_cpu_seconds();
        std::int64_t sink = 0;
        for (std::size_t k = 0; k < g.windows.size(); ++k) {
            decode<kStates, kNeighbours, kOffset>(streams[k].data(), g, g.windows[k].step, tables, q.data(), level.data());
            sink += q[0];
        }
        best_s = std::min(best_s, thread_cpu_seconds() - t0);
        g_sink = g_sink + static_cast<double>(sink);
    }
    const double us = best_s / static_cast<double>(g.windows.size()) * 1e6;
    double best_random = 1e300;
    for (int r = 0; r < repeats; ++r) {
        const double t0 = thread_cpu_seconds();
        std::int64_t sink = 0;
        for (std::size_t k : g.random_order) {
            decode<kStates, kNeighbours, kOffset>(streams[k].data(), g, g.windows[k].step, tables, q.data(), level.data());
            sink += q[0];
        }
        best_random = std::min(best_random, thread_cpu_seconds() - t0);
        g_sink = g_sink + static_cast<double>(sink);
    }
    const double random_us = best_random / static_cast<double>(g.random_order.size()) * 1e6;
    std::printf("  %-16s payload %9zu B (%+5.1f %%)  tables %5.0f B  decode %5.2f us/window in order, %5.2f random  "
                "(%.2fx faster than range)\n",
                label, bytes, 100.0 * (static_cast<double>(bytes) / static_cast<double>(range_bytes) - 1.0), table_bits / 8,
                us, random_us, range_us / us);
}

// Format 2's cold pose, stage by stage, at random coded windows (frame t random in the window):
// cumulative loops, so each stage's cost is the difference to the loop before.
void cold_breakdown(const Group& g, int repeats) {
    detail::WindowScratch s;
    g.model.prepare(s);
    LocalPose pose;
    std::mt19937_64 rng(11);
    std::vector<int> frames;
    for (std::size_t k = 0; k < g.random_order.size(); ++k)
        frames.push_back(static_cast<int>(rng() % static_cast<std::uint64_t>(g.model.window)));
    double stage[5];  // 4: decode + dequantize of the whole grid (before this branch), for comparison
    for (int upto = 0; upto < 5; ++upto) {
        double best_s = 1e300;
        for (int r = 0; r < repeats; ++r) {
            const double t0 = thread_cpu_seconds();
            double sink = 0;
            for (std::size_t n = 0; n < g.random_order.size(); ++n) {
                const std::size_t k = g.random_order[n];
                const detail::WindowEntry& e = g.entries[k];
                const auto& cls = g.classes[e.step];
                s.contexts = g.model.contexts;
                std::size_t nonzeros = 0;
                decode_coefficients(g.bytes.data() + g.payload + e.offset, e.size, cls.data(), cls.size(),
                                    g.model.grid(), s.contexts, s.q.data(), s.level.data(), s.nonzero.data(), &nonzeros);
                sink += s.q[0];
                if (upto == 4) {
                    g.model.dequantize(e.step, s.q.data(), cls.size(), s);
                    sink += s.g[0];
                    continue;
                }
                if (upto >= 1) {
                    // as GroupDecoder::load_window: only the nonzero coefficients
                    g.model.dequantize_nonzero(e.step, s.q.data(), s.nonzero.data(), nonzeros, s);
                    sink += s.g[0];
                }
                const detail::ClipEntry& c = g.model.clips[g.clip_of[k]];
                if (upto >= 2) {
                    g.model.frame_pose(c, s.g.data(), s.columns, s.rows, frames[n], s, s.p.data());
                    sink += s.p[0];
                }
                if (upto >= 3) {
                    g.model.local_of(c, s.p.data(), pose);
                    sink += pose.rotations[1].w();
                }
            }
            best_s = std::min(best_s, thread_cpu_seconds() - t0);
            g_sink = g_sink + sink;
        }
        stage[upto] = best_s / static_cast<double>(g.random_order.size()) * 1e6;
    }
    std::printf("  format 2 cold pose at random windows (us): range decode %.2f, dequantize %.2f (whole grid: %.2f), "
                "frame dofs %.2f, local pose %.2f, total %.2f\n",
                stage[0], stage[1] - stage[0], stage[4] - stage[0], stage[2] - stage[1], stage[3] - stage[2], stage[3]);
}

}  // namespace

int main(int argc, char** argv) {
    std::string cache, folders = "cmu-asfamc,cmu-walkrun-pfnn", errors = "1,0.5,0.1";
    int repeats = 3;
    std::setvbuf(stdout, nullptr, _IOLBF, 0);
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto next = [&]() -> std::string {
            if (i + 1 >= argc) throw std::runtime_error(a + " needs a value");
            return argv[++i];
        };
        if (a == "--cache") cache = next();
        else if (a == "--folders") folders = next();
        else if (a == "--errors") errors = next();
        else if (a == "--repeats") repeats = std::stoi(next());
        else {
            std::printf("usage: bench_coefficient_decode --cache DIR [--folders A,B] [--errors 1,0.5,0.1] [--repeats 3]\n");
            return a == "--help" ? 0 : 2;
        }
    }
    std::stringstream fs(folders);
    for (std::string folder; std::getline(fs, folder, ',');) {
        for (double E : parse_doubles(errors)) {
            std::ostringstream name;
            name << cache << "/" << folder << "_E" << E << ".mdbp";
            const Group g = load(name.str());
            std::size_t range_bytes = 0, coded = 0;
            double length_sum = 0;
            for (const Window& w : g.windows) {
                range_bytes += w.range_bytes;
                length_sum += w.length;
                for (std::int32_t v : w.q) coded += v != 0;
            }
            // format 2's range decoder on the same windows
            std::vector<std::int32_t> q(g.positions);
            std::vector<std::uint8_t> level(g.positions);
            double best_s = 1e300;
            ContextSet ctx;
            for (int r = 0; r < repeats; ++r) {
                const double t0 = thread_cpu_seconds();
                std::int64_t sink = 0;
                for (const detail::WindowEntry& e : g.entries) {
                    const auto& cls = g.classes[e.step];
                    ctx = g.model.contexts;
                    decode_coefficients(g.bytes.data() + g.payload + e.offset, e.size, cls.data(), cls.size(),
                                        g.model.grid(), ctx, q.data(), level.data());
                    sink += q[0];
                }
                best_s = std::min(best_s, thread_cpu_seconds() - t0);
                g_sink = g_sink + static_cast<double>(sink);
            }
            const double range_us = best_s / static_cast<double>(g.windows.size()) * 1e6;
            std::printf("%s E=%g: %zu coded windows, grid %zu positions, mean scan length %.0f, nonzero %.0f per window\n",
                        folder.c_str(), E, g.windows.size(), g.positions, length_sum / static_cast<double>(g.windows.size()),
                        static_cast<double>(coded) / static_cast<double>(g.windows.size()));
            std::printf("  %-16s payload %9zu B (group %zu B)  decode %5.2f us/window in order\n", "range (format 2)",
                        range_bytes, g.bytes.size(), range_us);
            cold_breakdown(g, repeats);
            run_rans<1, false, false>(g, repeats, "rans class/1", range_us, range_bytes);
            run_rans<2, false, false>(g, repeats, "rans class/2", range_us, range_bytes);
            run_rans<4, false, false>(g, repeats, "rans class/4", range_us, range_bytes);
            run_rans<2, false, true>(g, repeats, "rans shift/2", range_us, range_bytes);
            run_rans<4, false, true>(g, repeats, "rans shift/4", range_us, range_bytes);
            run_rans<2, true, false>(g, repeats, "rans nbr/2", range_us, range_bytes);
            run_rans<2, true, true>(g, repeats, "rans nbr+shift/2", range_us, range_bytes);
        }
    }
    return 0;
}
