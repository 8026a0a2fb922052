#include "mocapdb/packing/pose_index.hpp"

#include <algorithm>
#include <cstring>
#include <limits>
#include <string>
#if defined(__AVX2__)
#include <immintrin.h>
#endif

#include "group_model.hpp"
#include "lane4.hpp"

namespace mocapdb::packing {

namespace {

using detail::Lane4;

// Four levels as doubles (exact), from cells of any alignment.
inline Lane4 load_levels(const std::int8_t* p) {
#if defined(__AVX2__)
    std::int32_t four;
    std::memcpy(&four, p, sizeof four);
    return _mm256_cvtepi32_pd(_mm_cvtepi8_epi32(_mm_cvtsi32_si128(four)));
#else
    return Lane4{double(p[0]), double(p[1]), double(p[2]), double(p[3])};
#endif
}

inline Lane4 load_levels(const std::int16_t* p) {
#if defined(__AVX2__)
    return _mm256_cvtepi32_pd(_mm_cvtepi16_epi32(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(p))));
#else
    std::int16_t q[4];
    std::memcpy(q, p, sizeof q);
    return Lane4{double(q[0]), double(q[1]), double(q[2]), double(q[3])};
#endif
}

inline Lane4 load_levels(const std::int32_t* p) {
#if defined(__AVX2__)
    return _mm256_cvtepi32_pd(_mm_loadu_si128(reinterpret_cast<const __m128i*>(p)));
#else
    std::int32_t q[4];
    std::memcpy(q, p, sizeof q);
    return Lane4{double(q[0]), double(q[1]), double(q[2]), double(q[3])};
#endif
}

// acc[l] += (level · step) · v[c] for the columns [begin, end) of one block of 16 dof rows, whose
// levels (per column its 16) are of type Level.
template <typename Level>
const std::uint8_t* accumulate_columns(const std::uint8_t* bytes, std::size_t begin, std::size_t end, const Lane4& s,
                                       const double* v, Lane4* acc) {
    // Every column's bytes are a multiple of 16 and wider columns come first, so cells are aligned
    // for their width.
    const auto* column = reinterpret_cast<const Level*>(bytes);
    for (std::size_t c = begin; c < end; ++c, column += 16) {
        const Lane4 vc{v[c], v[c], v[c], v[c]};
        for (std::size_t l = 0; l < 4; ++l) acc[l] += load_levels(column + 4 * l) * s * vc;
    }
    return reinterpret_cast<const std::uint8_t*>(column);
}

// Bytes of a level of width code w (0, 1, 2).
std::size_t level_bytes(unsigned w) { return std::size_t{1} << w; }

// The width code of the fewest bits that hold the level.
unsigned width_of(std::int32_t level) {
    if (level >= -128 && level <= 127) return 0;
    if (level >= -32768 && level <= 32767) return 1;
    return 2;
}

void put_level(std::uint8_t* at, std::int32_t level, unsigned width) {
    if (width == 0) {
        const auto v = static_cast<std::int8_t>(level);
        std::memcpy(at, &v, sizeof v);
    } else if (width == 1) {
        const auto v = static_cast<std::int16_t>(level);
        std::memcpy(at, &v, sizeof v);
    } else {
        std::memcpy(at, &level, sizeof level);
    }
}

}  // namespace

PoseIndex::PoseIndex(const GroupDecoder& decoder) : decoder_(&decoder) {
    static_assert(kBlockRows == 16, "accumulate_columns works on 16 rows");
    if (decoder.format() == PackFormat::Runtime) return;  // its cold pose is already this fast: nothing to hold
    const detail::GroupModel& m = *decoder.model_;
    const std::size_t da = std::max<std::size_t>(1, m.active.size());
    const auto W = static_cast<std::size_t>(m.window);
    if (W > kMaxWindow)
        throw InvalidArgument("PoseIndex: windows of " + std::to_string(W) + " frames (the index holds at most " +
                              std::to_string(kMaxWindow) + ")");
    time_rows_.resize(W * W);
    for (std::size_t t = 0; t < W; ++t)
        for (std::size_t c = 0; c < W; ++c)
            time_rows_[t * W + c] = m.time_basis(static_cast<Eigen::Index>(t), static_cast<Eigen::Index>(c));

    struct Cell {
        std::size_t row, column;
        std::int32_t level;
    };
    std::vector<Cell> cells;
    std::vector<std::uint8_t> width;  // per (block, column) of the window: its width code
    std::vector<std::size_t> offset;  // per (block, column): bytes from the window's first cell
    std::vector<std::size_t> kept;    // per block: time columns up to its last nonzero one
    detail::WindowScratch& s = detail::thread_scratch();
    windows_.resize(m.windows.size());
    for (std::size_t i = 0; i < m.windows.size(); ++i) {
        const detail::WindowEntry& e = m.windows[i];
        Window& out = windows_[i];
        out.begin = cells_.size();
        out.blocks = blocks_.size();
        if (e.step == detail::kRawStep) continue;
        const std::size_t n = decoder.decode_levels(e, s);
        cells.clear();
        std::size_t rows = 0, columns = 0;
        for (std::size_t k = 0; k < n; ++k) {
            const std::uint32_t place = m.scan[s.nonzero[k]];
            cells.push_back({place % da, place / da, s.q[s.nonzero[k]]});
            rows = std::max(rows, place % da + 1);  // as GroupModel::dequantize_nonzero
            columns = std::max(columns, place / da + 1);
        }
        const std::size_t blocks = (rows + kBlockRows - 1) / kBlockRows;
        // A column's width: the fewest bits that hold its levels and those of every later column of
        // its block (so wider columns come first). Energy falls along the columns: the large levels
        // sit in the first few, and most columns take 8 bits.
        width.assign(blocks * columns, 0);
        kept.assign(blocks, 0);
        for (const Cell& c : cells) {
            std::uint8_t& w = width[c.row / kBlockRows * columns + c.column];
            w = static_cast<std::uint8_t>(std::max<unsigned>(w, width_of(c.level)));
            std::size_t& k = kept[c.row / kBlockRows];
            k = std::max(k, c.column + 1);
        }
        offset.assign(blocks * columns, 0);
        std::size_t bytes = 0;
        for (std::size_t b = 0; b < blocks; ++b) {
            std::uint8_t* w = width.data() + b * columns;
            for (std::size_t c = kept[b]; c-- > 1;) w[c - 1] = std::max(w[c - 1], w[c]);
            BlockEntry ends{};
            for (std::size_t c = 0; c < kept[b]; ++c) {
                offset[b * columns + c] = bytes;
                bytes += kBlockRows * level_bytes(w[c]);
                ++column_widths_[w[c]];
                if (w[c] == 2) ends[0] = static_cast<std::uint16_t>(c + 1);
                if (w[c] >= 1) ends[1] = static_cast<std::uint16_t>(c + 1);
            }
            ends[2] = static_cast<std::uint16_t>(kept[b]);
            blocks_.push_back(ends);
        }
        cells_.resize(cells_.size() + bytes, 0);
        for (const Cell& c : cells) {
            const std::size_t at = c.row / kBlockRows * columns + c.column;
            put_level(cells_.data() + out.begin + offset[at] + (c.row % kBlockRows) * level_bytes(width[at]), c.level,
                      width[at]);
        }
        out.rows = static_cast<std::uint32_t>(rows);
        out.step = detail::step_of(e.step);
        coefficients_ += n;
    }
    blocks_.shrink_to_fit();
    cells_.shrink_to_fit();
}

std::size_t PoseIndex::memory_bytes() const {
    return cells_.capacity() + blocks_.capacity() * sizeof(BlockEntry) + windows_.capacity() * sizeof(Window) +
           time_rows_.capacity() * sizeof(double);
}

const double* PoseIndex::dofs(std::size_t clip, std::size_t global, std::size_t t) const {
    const detail::GroupModel& m = *decoder_->model_;
    const Window& win = windows_[global];
    const std::size_t blocks = (win.rows + kBlockRows - 1) / kBlockRows;
    const BlockEntry* entry = blocks_.data() + win.blocks;
    // A random window is not in cache: its cells are requested at once, not a line at a time as the
    // loop reaches them (prefetching is a hint: no effect on the result).
    std::size_t bytes = 0;
    for (std::size_t b = 0; b < blocks; ++b) bytes += kBlockRows * (2u * entry[b][0] + entry[b][1] + entry[b][2]);
    const std::uint8_t* cells = cells_.data() + win.begin;
    for (std::size_t at = 0; at < bytes; at += 64) __builtin_prefetch(cells + at);
    detail::WindowScratch& s = detail::thread_scratch();
    m.prepare(s);
    double* y = s.y.data();
    const double* v = time_rows_.data() + t * static_cast<std::size_t>(m.window);
    const Lane4 step{win.step, win.step, win.step, win.step};
    for (std::size_t b = 0; b < blocks; ++b) {
        // Each y element adds its terms in ascending column from +0, as GroupModel::frame_pose sums
        // the dense grid (whose other terms are zeros: no change in bits).
        Lane4 acc[4];
        for (Lane4& a : acc) a = Lane4{0.0, 0.0, 0.0, 0.0};
        cells = accumulate_columns<std::int32_t>(cells, 0, entry[b][0], step, v, acc);
        cells = accumulate_columns<std::int16_t>(cells, entry[b][0], entry[b][1], step, v, acc);
        cells = accumulate_columns<std::int8_t>(cells, entry[b][1], entry[b][2], step, v, acc);
        double out[kBlockRows];
        std::memcpy(out, acc, sizeof out);
        std::copy(out, out + std::min(kBlockRows, win.rows - b * kBlockRows), y + b * kBlockRows);
    }
    m.pose_of(m.clips[clip], y, static_cast<int>(win.rows), s, s.p.data());
    return s.p.data();
}

const double* PoseIndex::frame_dofs(std::size_t clip, std::size_t frame) const {
    decoder_->check(clip, frame);
    const detail::GroupModel& m = *decoder_->model_;
    const auto W = static_cast<std::size_t>(m.window);
    const std::size_t global = m.clips[clip].first_window + frame / W;
    return m.windows[global].step == detail::kRawStep ? nullptr : dofs(clip, global, frame % W);
}

void PoseIndex::pose(std::size_t clip, std::size_t frame, double* out_row) const {
    if (decoder_->format() == PackFormat::Runtime) return decoder_->decode_pose(clip, frame, out_row);
    const detail::GroupModel& m = *decoder_->model_;
    if (const double* p = frame_dofs(clip, frame)) m.row_of(m.clips[clip], p, out_row);
    else decoder_->decode_pose(clip, frame, out_row);  // a window stored as source rows
}

void PoseIndex::local_pose(std::size_t clip, std::size_t frame, LocalPose& out) const {
    if (decoder_->format() == PackFormat::Runtime) return decoder_->decode_local_pose(clip, frame, out);
    const detail::GroupModel& m = *decoder_->model_;
    if (const double* p = frame_dofs(clip, frame)) m.local_of(m.clips[clip], p, out);
    else decoder_->decode_local_pose(clip, frame, out);
}

}  // namespace mocapdb::packing
