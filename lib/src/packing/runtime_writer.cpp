#include "runtime_writer.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <string>

#include "mocapdb/packing/packed_group.hpp"
#include "runtime_bits.hpp"
#include "runtime_codes.hpp"

namespace mocapdb::packing::detail {

namespace {

/// Per clip and row of the keys: the width (the one that codes the row smallest with escapes), the
/// center every value is stored relative to, and the escape width (> width: the row has escapes).
struct RtKeyRows {
    std::vector<std::uint8_t> width, full;
    std::vector<std::int32_t> center;
};

/// The width that codes `values` smallest when a value outside (-2^(w-1), 2^(w-1)) is stored as
/// -2^(w-1) and then at `full` bits (full: the width that holds them all).
int rt_escape_width(const std::vector<std::int64_t>& values, int full) {
    const auto n = static_cast<double>(values.size());
    double best = static_cast<double>(full) * n;
    int best_w = full;
    for (int x = 1; x < full; ++x) {
        double cost = static_cast<double>(x) * n;
        for (std::int64_t v : values)
            if (!(v > -(std::int64_t{1} << (x - 1)) && v < (std::int64_t{1} << (x - 1)))) cost += full;
        if (cost < best) {
            best = cost;
            best_w = x;
        }
    }
    return best_w;
}

RtKeyRows rt_key_rows(const RuntimeCoefficients& r, std::size_t Da) {
    RtKeyRows f;
    const std::size_t clips = r.clip_first.size() - 1;
    f.width.assign(clips * Da, 0);
    f.center.assign(clips * Da, 0);
    f.full.assign(clips * Da, 0);
    for (std::size_t i = 0; i < clips; ++i) {
        const std::size_t first = r.clip_first[i], last = r.clip_first[i + 1];
        if (first == last) continue;
        std::uint8_t* w = f.width.data() + i * Da;
        std::int32_t* center = f.center.data() + i * Da;
        std::uint8_t* full = f.full.data() + i * Da;
        for (std::size_t d = 0; d < Da; ++d) {
            std::int32_t lo = r.entries[first].key[d], hi = lo;
            for (std::size_t e = first; e < last; ++e) {
                lo = std::min(lo, r.entries[e].key[d]);
                hi = std::max(hi, r.entries[e].key[d]);
            }
            center[d] = static_cast<std::int32_t>((static_cast<std::int64_t>(lo) + hi) >> 1);
            std::vector<std::int64_t> row;
            int widest = 0;
            for (std::size_t e = first; e < last; ++e) {
                row.push_back(static_cast<std::int64_t>(r.entries[e].key[d]) - center[d]);
                widest = std::max(widest, rt_twos_bits(row.back()));
            }
            if (widest > kKeyMaxWidth) throw PackingFailed("runtime tier: a key row needs more than 40 bits");
            full[d] = static_cast<std::uint8_t>(widest);
            w[d] = static_cast<std::uint8_t>(rt_escape_width(row, widest));
        }
    }
    return f;
}

/// Key values v of clip i at f's widths: the slots, then the escaped values.
void rt_write_key(RtBitWriter& out, const RtKeyRows& f, std::size_t i, std::size_t Da,
                  const std::vector<std::int32_t>& v) {
    const std::uint8_t* w = f.width.data() + i * Da;
    const std::int32_t* center = f.center.data() + i * Da;
    const std::uint8_t* full = f.full.data() + i * Da;
    std::vector<std::pair<std::int64_t, int>> escaped;
    for (std::size_t d = 0; d < Da; ++d) {
        const std::int64_t x = static_cast<std::int64_t>(v[d]) - center[d];
        if (full[d] > w[d] && !(x > -(std::int64_t{1} << (w[d] - 1)) && x < (std::int64_t{1} << (w[d] - 1)))) {
            out.put(static_cast<std::uint64_t>(-(std::int64_t{1} << (w[d] - 1))), w[d]);
            escaped.push_back({x, full[d]});
        } else {
            out.put(static_cast<std::uint64_t>(x), w[d]);
        }
    }
    for (const auto& [x, fw] : escaped) out.put(static_cast<std::uint64_t>(x), fw);
}

/// The quad codes of a group: per context (level, row >> kQuadShift) code lengths and codes.
struct RtQuadCodes {
    int per_level = 0;
    std::vector<std::vector<std::uint8_t>> lengths;
    std::vector<std::vector<std::uint32_t>> codes;
    std::size_t context(int level, int row) const {
        return static_cast<std::size_t>((level - 1) * per_level + (row >> kQuadShift));
    }
};

/// Calls fn(context, symbol, width, row) for each quad symbol of column v (width: the raw values'
/// width of a wide quad, else 0).
template <class Fn>
void rt_each_quad(const RtQuadCodes& qc, int level, const std::vector<std::int32_t>& v, Fn fn) {
    const int Da = static_cast<int>(v.size());
    int n = Da;
    while (n > 0 && v[static_cast<std::size_t>(n - 1)] == 0) --n;
    int d = 0;
    for (; d < n; d += 4) {
        int mx = 0, pattern = 0, w = 0;
        for (int k = d; k < d + 4; ++k) {
            const std::int32_t q = k < Da ? v[static_cast<std::size_t>(k)] : 0;
            mx = std::max(mx, std::abs(q));
            w = std::max(w, rt_twos_bits(q));
            pattern = pattern * 3 + (std::clamp(q, -1, 1) + 1);
        }
        if (mx <= 1) {
            fn(qc.context(level, d), 1 + pattern, 0, d);
        } else {
            if (w > kQuadMaxWidth) throw PackingFailed("runtime tier: a detail value needs more than 32 bits");
            fn(qc.context(level, d), kQuadWideSymbol + w, w, d);
        }
    }
    if (d < Da) fn(qc.context(level, d), kQuadEndSymbol, 0, d);
}

void rt_write_quads(RtBitWriter& out, const RtQuadCodes& qc, int level, const std::vector<std::int32_t>& v) {
    const int Da = static_cast<int>(v.size());
    rt_each_quad(qc, level, v, [&](std::size_t c, int s, int w, int d) {
        out.put(qc.codes[c][static_cast<std::size_t>(s)], qc.lengths[c][static_cast<std::size_t>(s)]);
        for (int k = d; w && k < d + 4; ++k)
            out.put(static_cast<std::uint64_t>(static_cast<std::int64_t>(k < Da ? v[static_cast<std::size_t>(k)] : 0)),
                    w);
    });
}

std::size_t rt_quad_bits(const RtQuadCodes& qc, int level, const std::vector<std::int32_t>& v) {
    std::size_t bits = 0;
    rt_each_quad(qc, level, v, [&](std::size_t c, int s, int w, int) {
        bits += qc.lengths[c][static_cast<std::size_t>(s)] + 4 * static_cast<std::size_t>(w);
    });
    return bits;
}

/// Per clip the entries' step fields: field 0 the key's step minus the clip's base, field l (1 ..
/// levels) level l's step minus the clip's base, times kRuntimePredictors plus the level's predictor
/// at levels >= 2; each at the clip's width for the field. A level whose columns are all zero in a
/// window decodes the same at any step: its field takes the base.
struct RtStepFields {
    std::vector<std::array<int, kMaxLevels + 1>> base, width;
    static bool zero_level(const RuntimeEntry& e, const std::vector<int>& tree_level, int l) {
        for (std::size_t c = 0; c < e.columns.size(); ++c)
            if (tree_level[c] == l)
                for (std::int32_t v : e.columns[c])
                    if (v) return false;
        return true;
    }
    std::uint64_t value(std::size_t clip, int l, const RuntimeEntry& e, const std::vector<int>& tree_level) const {
        const int b = base[clip][static_cast<std::size_t>(l)];
        if (l == 0) return static_cast<std::uint64_t>(e.key_step - b);
        const auto k = static_cast<std::size_t>(l - 1);
        const int step = zero_level(e, tree_level, l) ? b : e.level_step[k];
        return static_cast<std::uint64_t>(l == 1 ? step - b : (step - b) * kRuntimePredictors + e.level_predictor[k]);
    }
    RtStepFields(const RuntimeCoefficients& r, const std::vector<int>& tree_level) {
        const std::size_t clips = r.clip_first.size() - 1;
        base.assign(clips, {});
        width.assign(clips, {});
        for (std::size_t i = 0; i < clips; ++i) {
            std::array<int, kMaxLevels + 1> lo, hi;
            lo.fill(kMaxStep + 1);
            hi.fill(-1);
            for (std::size_t k = r.clip_first[i]; k < r.clip_first[i + 1]; ++k) {
                const RuntimeEntry& e = r.entries[k];
                lo[0] = std::min(lo[0], e.key_step);
                hi[0] = std::max(hi[0], e.key_step);
                if (e.step < 0) continue;
                for (int l = 1; l <= r.levels; ++l)
                    if (!zero_level(e, tree_level, l)) {
                        const auto L = static_cast<std::size_t>(l);
                        lo[L] = std::min(lo[L], e.level_step[L - 1]);
                        hi[L] = std::max(hi[L], e.level_step[L - 1]);
                    }
            }
            for (int l = 0; l <= r.levels; ++l) {
                const auto L = static_cast<std::size_t>(l);
                base[i][L] = hi[L] < 0 ? 0 : lo[L];
            }
            std::uint64_t largest[kMaxLevels + 1] = {0};
            for (std::size_t k = r.clip_first[i]; k < r.clip_first[i + 1]; ++k)
                for (int l = 0; l <= (r.entries[k].step < 0 ? 0 : r.levels); ++l)
                    largest[l] = std::max(largest[l], value(i, l, r.entries[k], tree_level));
            for (int l = 0; l <= r.levels; ++l) width[i][static_cast<std::size_t>(l)] = rt_bit_length(largest[l]);
        }
    }
};

/// A window: step fields, directory (widths: given per clip, or nullptr: in the window; need: only each
/// level's largest width into need[l], nothing written), columns in tree order.
void rt_write_window(RtBitWriter& out, const RtQuadCodes& qc, const RuntimeEntry& e, const std::vector<int>& tree_level,
                     int levels, int stored, const int* widths, int* need, const RtStepFields* fields = nullptr,
                     std::size_t clip = 0) {
    std::vector<std::size_t> size;
    for (std::size_t i = 0; i < e.columns.size(); ++i) size.push_back(rt_quad_bits(qc, tree_level[i], e.columns[i]));
    std::vector<std::vector<std::size_t>> left(static_cast<std::size_t>(levels));
    for (std::size_t i = 0; i < e.columns.size(); ++i) {
        const int l = tree_level[i];
        if (l >= levels) continue;
        const std::size_t span = (std::size_t{1} << (levels - l)) - 1;
        std::size_t s = 0;
        for (std::size_t k = i + 1; k <= i + span; ++k) s += size[k];
        left[static_cast<std::size_t>(l)].push_back(s);
    }
    std::vector<int> width(static_cast<std::size_t>(levels), 0);
    for (int l = 1; l <= stored; ++l) {
        for (std::size_t s : left[static_cast<std::size_t>(l)])
            width[static_cast<std::size_t>(l)] = std::max(width[static_cast<std::size_t>(l)], rt_bit_length(s));
        if (width[static_cast<std::size_t>(l)] > 31)
            throw PackingFailed("runtime tier: a window of more than 2^31 bits");
        if (need) need[l] = std::max(need[l], width[static_cast<std::size_t>(l)]);
    }
    if (need) return;
    for (int l = 1; l <= levels; ++l)
        out.put(fields->value(clip, l, e, tree_level), fields->width[clip][static_cast<std::size_t>(l)]);
    for (int l = 1; l <= stored; ++l) {
        if (widths) width[static_cast<std::size_t>(l)] = widths[l];
        else out.put(static_cast<std::uint64_t>(width[static_cast<std::size_t>(l)]), 5);
    }
    for (int l = 1; l <= stored; ++l)
        for (std::size_t s : left[static_cast<std::size_t>(l)]) out.put(s, width[static_cast<std::size_t>(l)]);
    for (std::size_t i = 0; i < e.columns.size(); ++i) rt_write_quads(out, qc, tree_level[i], e.columns[i]);
}

void rt_put_u32(std::vector<std::uint8_t>& out, std::size_t at, std::size_t v) {
    if (v > 0xffffffffu) throw PackingFailed("runtime tier: a section of more than 2^32 bytes");
    for (int k = 0; k < 4; ++k) out[at + static_cast<std::size_t>(k)] = static_cast<std::uint8_t>(v >> (8 * k));
}

}  // namespace

std::vector<std::uint8_t> write_runtime_body(const RuntimeCoefficients& r, int Da, int stored,
                                             RuntimeBodyParts* parts) {
    const auto n = static_cast<std::size_t>(Da);
    const std::size_t clips = r.clip_first.size() - 1;
    const int levels = r.levels;
    stored = std::clamp(stored, 0, std::max(0, levels - 1));
    std::vector<int> tree_level, tree_frame;
    runtime_tree_order(r.window, tree_level, tree_frame);

    // Quad codes trained on the group's columns.
    RtQuadCodes qc;
    qc.per_level = quad_contexts_per_level(Da);
    const std::size_t contexts = static_cast<std::size_t>(levels * qc.per_level);
    std::vector<std::vector<std::size_t>> hist(contexts, std::vector<std::size_t>(kQuadAlphabet, 0));
    for (const RuntimeEntry& e : r.entries)
        for (std::size_t i = 0; i < e.columns.size(); ++i)
            rt_each_quad(qc, tree_level[i], e.columns[i],
                         [&](std::size_t c, int s, int, int) { ++hist[c][static_cast<std::size_t>(s)]; });
    for (const auto& h : hist) {
        qc.lengths.push_back(rt_code_lengths(h, kQuadCodeBits));
        qc.codes.push_back(rt_canonical_codes(qc.lengths.back()));
    }
    const RtKeyRows keys = rt_key_rows(r, n);
    const RtStepFields fields(r, tree_level);

    // Entries, clip by clip; per clip the directory's widths in the clip table or in each window,
    // whichever gives the clip's entries fewer bytes.
    RtBitWriter entries;
    std::vector<std::size_t> offsets;
    std::vector<std::array<int, kMaxLevels + 1>> clip_widths(clips);
    std::vector<char> widths_by_clip(clips, 0);
    for (std::size_t i = 0; i < clips; ++i) {
        const std::size_t first = r.clip_first[i], last = r.clip_first[i + 1];
        int widths[kMaxLevels + 1] = {0};
        for (std::size_t k = first; k < last; ++k)
            if (r.entries[k].step >= 0)
                rt_write_window(entries, qc, r.entries[k], tree_level, levels, stored, nullptr, widths);
        auto entry = [&](RtBitWriter& o, std::size_t k, const int* w) {
            const RuntimeEntry& e = r.entries[k];
            o.put(fields.value(i, 0, e, tree_level), fields.width[i][0]);
            rt_write_key(o, keys, i, n, e.key);
            if (e.step >= 0) rt_write_window(o, qc, e, tree_level, levels, stored, w, nullptr, &fields, i);
            o.align();
        };
        std::size_t per_clip = 0, per_window = 0;
        if (stored > 0)
            for (std::size_t k = first; k < last; ++k) {
                RtBitWriter a, b;
                entry(a, k, widths);
                entry(b, k, nullptr);
                per_clip += a.bytes.size();
                per_window += b.bytes.size();
            }
        const bool by_clip = stored > 0 && 8 * per_clip + 5 * static_cast<std::size_t>(stored) < 8 * per_window;
        clip_widths[i].fill(0);
        widths_by_clip[i] = by_clip ? 1 : 0;
        if (by_clip)
            for (int l = 1; l <= stored; ++l) clip_widths[i][static_cast<std::size_t>(l)] = widths[l];
        for (std::size_t k = first; k < last; ++k) {
            offsets.push_back(entries.bytes.size());
            entry(entries, k, by_clip ? widths : nullptr);
        }
    }
    entries.align();

    // Offsets: per clip each entry's byte offset minus the clip's line (origin + k · slope), at the
    // clip's width; the slope (near the clip's mean entry size) whose residuals span the fewest values.
    RtBitWriter offset_bits;
    std::vector<std::int64_t> origin(clips, 0), slope(clips, 0);
    std::vector<int> offset_width(clips, 0);
    for (std::size_t i = 0; i < clips; ++i) {
        const std::size_t first = r.clip_first[i], last = r.clip_first[i + 1];
        if (first == last) continue;
        auto at = [&](std::size_t k) { return static_cast<std::int64_t>(offsets[first + k]); };
        const std::size_t m = last - first;
        std::vector<std::int64_t> candidates{0};
        if (m > 1) {
            // The line through the ends, and the least-squares line.
            const std::int64_t ends = (at(m - 1) - at(0)) / static_cast<std::int64_t>(m - 1);
            double sk = 0, so = 0, skk = 0, sko = 0;
            for (std::size_t k = 0; k < m; ++k) {
                const auto x = static_cast<double>(k), o = static_cast<double>(at(k));
                sk += x;
                so += o;
                skk += x * x;
                sko += x * o;
            }
            const double nm = static_cast<double>(m);
            const auto ls = static_cast<std::int64_t>(std::llround((nm * sko - sk * so) / (nm * skk - sk * sk)));
            for (std::int64_t c : {ends, ls})
                for (std::int64_t d = -2; d <= 2; ++d)
                    if (c + d >= 0) candidates.push_back(c + d);
        }
        std::int64_t best = -1;
        for (std::int64_t c : candidates) {
            std::int64_t lo = at(0), hi = at(0);
            for (std::size_t k = 0; k < m; ++k) {
                lo = std::min(lo, at(k) - static_cast<std::int64_t>(k) * c);
                hi = std::max(hi, at(k) - static_cast<std::int64_t>(k) * c);
            }
            if (best < 0 || hi - lo < best) {
                best = hi - lo;
                slope[i] = c;
                origin[i] = lo;
            }
        }
        if (slope[i] >= (std::int64_t{1} << 24)) throw PackingFailed("runtime tier: entries of more than 2^24 bytes");
        offset_width[i] = rt_bit_length(static_cast<std::uint64_t>(best));
        for (std::size_t k = 0; k < m; ++k)
            offset_bits.put(static_cast<std::uint64_t>(at(k) - static_cast<std::int64_t>(k) * slope[i] - origin[i]),
                            offset_width[i]);
    }
    offset_bits.align();

    // Side stream.
    RtBitWriter side;
    for (const auto& lengths : qc.lengths) rt_write_lengths(side, lengths, kQuadSymbolBits);
    std::vector<int> largest(n, 0);
    for (std::size_t i = 0; i < clips; ++i)
        for (std::size_t d = 0; d < n; ++d) largest[d] = std::max<int>(largest[d], keys.width[i * n + d]);
    std::vector<std::size_t> delta_count(kSideAlphabet, 0), center_count(kSideAlphabet, 0),
        extra_count(kSideAlphabet, 0);
    for (std::size_t i = 0; i < clips; ++i)
        for (std::size_t d = 0; d < n; ++d) {
            ++delta_count[static_cast<std::size_t>(largest[d] - keys.width[i * n + d])];
            ++center_count[static_cast<std::size_t>(rt_twos_bits(keys.center[i * n + d]))];
            ++extra_count[static_cast<std::size_t>(keys.full[i * n + d] - keys.width[i * n + d])];
        }
    const auto delta_lengths = rt_code_lengths(delta_count, kSideCodeBits);
    const auto center_lengths = rt_code_lengths(center_count, kSideCodeBits);
    const auto extra_lengths = rt_code_lengths(extra_count, kSideCodeBits);
    const auto delta_codes = rt_canonical_codes(delta_lengths);
    const auto center_codes = rt_canonical_codes(center_lengths);
    const auto extra_codes = rt_canonical_codes(extra_lengths);
    for (std::size_t d = 0; d < n; ++d) side.put(static_cast<std::uint64_t>(largest[d]), kSideSymbolBits);
    rt_write_lengths(side, delta_lengths, kSideSymbolBits);
    rt_write_lengths(side, center_lengths, kSideSymbolBits);
    rt_write_lengths(side, extra_lengths, kSideSymbolBits);
    for (std::size_t i = 0; i < clips; ++i) {
        for (int l = 0; l <= levels; ++l) {
            side.put(static_cast<std::uint64_t>(fields.base[i][static_cast<std::size_t>(l)]), 8);
            side.put(static_cast<std::uint64_t>(fields.width[i][static_cast<std::size_t>(l)]), 4);
        }
        for (std::size_t d = 0; d < n; ++d) {
            const auto delta = static_cast<std::size_t>(largest[d] - keys.width[i * n + d]);
            const std::int32_t center = keys.center[i * n + d];
            const auto cw = static_cast<std::size_t>(rt_twos_bits(center));
            const auto extra = static_cast<std::size_t>(keys.full[i * n + d] - keys.width[i * n + d]);
            side.put(delta_codes[delta], delta_lengths[delta]);
            side.put(center_codes[cw], center_lengths[cw]);
            side.put(static_cast<std::uint64_t>(static_cast<std::int64_t>(center)), static_cast<int>(cw));
            side.put(extra_codes[extra], extra_lengths[extra]);
        }
    }
    for (std::size_t i = 0; i < clips; ++i) {
        const bool by_clip = widths_by_clip[i] != 0;
        side.put(by_clip ? 1 : 0, 1);
        if (by_clip)
            for (int l = 1; l <= stored; ++l)
                side.put(static_cast<std::uint64_t>(clip_widths[i][static_cast<std::size_t>(l)]), 5);
        side.put(static_cast<std::uint64_t>(origin[i]), 34);
        side.put(static_cast<std::uint64_t>(slope[i]), 24);
        side.put(static_cast<std::uint64_t>(offset_width[i]), 6);
    }
    side.align();

    std::vector<std::uint8_t> out(kRuntimeHeaderBytes, 0);
    out[0] = kRuntimeVersion;
    out[1] = static_cast<std::uint8_t>(levels);
    out[2] = static_cast<std::uint8_t>(stored);
    out[3] = static_cast<std::uint8_t>(r.key_offset);
    out[4] = static_cast<std::uint8_t>(n & 0xff);
    out[5] = static_cast<std::uint8_t>(n >> 8);
    out[6] = out[7] = 0;
    rt_put_u32(out, 8, clips);
    rt_put_u32(out, 12, side.bytes.size());
    rt_put_u32(out, 16, offset_bits.bytes.size());
    rt_put_u32(out, 20, entries.bytes.size());
    out.insert(out.end(), side.bytes.begin(), side.bytes.end());
    out.insert(out.end(), offset_bits.bytes.begin(), offset_bits.bytes.end());
    out.insert(out.end(), entries.bytes.begin(), entries.bytes.end());
    out.resize(out.size() + kRuntimeSlack, 0);
    if (parts) {
        parts->header = kRuntimeHeaderBytes;
        parts->side = side.bytes.size();
        parts->offsets = offset_bits.bytes.size();
        parts->entries = entries.bytes.size();
        parts->slack = kRuntimeSlack;
    }
    return out;
}

}  // namespace mocapdb::packing::detail
