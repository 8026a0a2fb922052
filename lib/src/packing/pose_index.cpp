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

// y[i] = sum over c < columns of (level[i][c] · step) · v[c], i < rows <= 16, for one block of 16 dof
// rows (cells: per column its 16 levels). Every y element adds its terms in ascending column from
// +0, as GroupModel::frame_pose sums the dense grid (whose other terms are zeros: no change in bits).
template <typename Level>
void accumulate_block(const std::uint8_t* bytes, std::size_t columns, double step, const double* v, double* y,
                      std::size_t rows) {
    // Every block's bytes are a multiple of 16, so cells are aligned for their width.
    const auto* cells = reinterpret_cast<const Level*>(bytes);
    Lane4 acc[4];
    for (Lane4& a : acc) a = Lane4{0.0, 0.0, 0.0, 0.0};
    const Lane4 s{step, step, step, step};
    for (std::size_t c = 0; c < columns; ++c) {
        const Lane4 vc{v[c], v[c], v[c], v[c]};
        const Level* column = cells + 16 * c;
        for (std::size_t l = 0; l < 4; ++l) acc[l] += load_levels(column + 4 * l) * s * vc;
    }
    double out[16];
    std::memcpy(out, acc, sizeof out);
    std::copy(out, out + rows, y);
}

// Bytes of a level of width code w (0, 1, 2).
std::size_t level_bytes(unsigned w) { return std::size_t{1} << w; }

// The width code of the fewest bits that hold every level in [low, high].
unsigned width_of(std::int32_t low, std::int32_t high) {
    if (low >= -128 && high <= 127) return 0;
    if (low >= -32768 && high <= 32767) return 1;
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
    static_assert(kBlockRows == 16, "accumulate_block works on 16 rows");
    const detail::GroupModel& m = *decoder.model_;
    const std::size_t da = std::max<std::size_t>(1, m.active.size());
    const auto W = static_cast<std::size_t>(m.window);
    if (W >= (std::size_t{1} << kWidthShift))
        throw InvalidArgument("PoseIndex: windows of " + std::to_string(W) + " frames (the index holds at most " +
                              std::to_string((1u << kWidthShift) - 1) + ")");
    time_rows_.resize(W * W);
    for (std::size_t t = 0; t < W; ++t)
        for (std::size_t c = 0; c < W; ++c) time_rows_[t * W + c] = m.time_basis(static_cast<Eigen::Index>(t), static_cast<Eigen::Index>(c));

    struct Cell {
        std::size_t row, column;
        std::int32_t level;
    };
    struct Block {
        std::size_t columns = 0, offset = 0;  // offset: bytes from the window's first cell
        std::int32_t low = 0, high = 0;
    };
    std::vector<Cell> cells;
    std::vector<Block> blocks;
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
        std::size_t rows = 0;
        for (std::size_t k = 0; k < n; ++k) {
            const std::uint32_t place = m.scan[s.nonzero[k]];
            cells.push_back({place % da, place / da, s.q[s.nonzero[k]]});
            rows = std::max(rows, place % da + 1);  // as GroupModel::dequantize_nonzero
        }
        blocks.assign((rows + kBlockRows - 1) / kBlockRows, Block{});
        for (const Cell& c : cells) {
            Block& b = blocks[c.row / kBlockRows];
            b.columns = std::max(b.columns, c.column + 1);
            b.low = std::min(b.low, c.level);
            b.high = std::max(b.high, c.level);
        }
        // The window's cells: block after block, column after column, 16 levels each.
        std::size_t bytes = 0;
        for (Block& b : blocks) {
            const unsigned width = width_of(b.low, b.high);
            b.offset = bytes;
            bytes += b.columns * kBlockRows * level_bytes(width);
            blocks_.push_back(static_cast<std::uint16_t>(b.columns | width << kWidthShift));
            ++block_widths_[width];
        }
        cells_.resize(cells_.size() + bytes, 0);
        for (const Cell& c : cells) {
            const Block& b = blocks[c.row / kBlockRows];
            const unsigned width = width_of(b.low, b.high);
            put_level(cells_.data() + out.begin + b.offset + (c.column * kBlockRows + c.row % kBlockRows) * level_bytes(width),
                      c.level, width);
        }
        out.rows = static_cast<std::uint32_t>(rows);
        out.step = detail::step_of(e.step);
        coefficients_ += n;
    }
    blocks_.shrink_to_fit();
    cells_.shrink_to_fit();
}

std::size_t PoseIndex::memory_bytes() const {
    return cells_.capacity() + blocks_.capacity() * sizeof(std::uint16_t) + windows_.capacity() * sizeof(Window) +
           time_rows_.capacity() * sizeof(double);
}

const double* PoseIndex::dofs(std::size_t clip, std::size_t global, std::size_t t) const {
    const detail::GroupModel& m = *decoder_->model_;
    const Window& win = windows_[global];
    const std::size_t blocks = (win.rows + kBlockRows - 1) / kBlockRows;
    const std::uint16_t* entry = blocks_.data() + win.blocks;
    const std::uint16_t column_mask = (1u << kWidthShift) - 1;
    // A random window is not in cache: its cells are requested at once, not a line at a time as the
    // loop reaches them (prefetching is a hint: no effect on the result).
    std::size_t bytes = 0;
    for (std::size_t b = 0; b < blocks; ++b) bytes += (entry[b] & column_mask) * kBlockRows * level_bytes(entry[b] >> kWidthShift);
    const std::uint8_t* cells = cells_.data() + win.begin;
    for (std::size_t at = 0; at < bytes; at += 64) __builtin_prefetch(cells + at);
    detail::WindowScratch& s = detail::thread_scratch();
    m.prepare(s);
    double* y = s.y.data();
    const double* v = time_rows_.data() + t * static_cast<std::size_t>(m.window);
    for (std::size_t b = 0; b < blocks; ++b) {
        const std::size_t columns = entry[b] & column_mask;
        const unsigned width = entry[b] >> kWidthShift;
        const std::size_t rows = std::min(kBlockRows, win.rows - b * kBlockRows);
        double* yb = y + b * kBlockRows;
        if (width == 0)
            accumulate_block<std::int8_t>(cells, columns, win.step, v, yb, rows);
        else if (width == 1)
            accumulate_block<std::int16_t>(cells, columns, win.step, v, yb, rows);
        else
            accumulate_block<std::int32_t>(cells, columns, win.step, v, yb, rows);
        cells += columns * kBlockRows * level_bytes(width);
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
    const detail::GroupModel& m = *decoder_->model_;
    if (const double* p = frame_dofs(clip, frame))
        m.row_of(m.clips[clip], p, out_row);
    else
        decoder_->decode_pose(clip, frame, out_row);  // a window stored as source rows
}

void PoseIndex::local_pose(std::size_t clip, std::size_t frame, LocalPose& out) const {
    const detail::GroupModel& m = *decoder_->model_;
    if (const double* p = frame_dofs(clip, frame))
        m.local_of(m.clips[clip], p, out);
    else
        decoder_->decode_local_pose(clip, frame, out);
}

}  // namespace mocapdb::packing
