#include "mocapdb/packing/pose_index.hpp"

#include <algorithm>
#include <string>
#include <utility>

#include "group_model.hpp"

namespace mocapdb::packing {

namespace {

// Bits that hold 0 .. n - 1.
unsigned bits_for(std::uint64_t n) {
    unsigned b = 0;
    while ((std::uint64_t{1} << b) < n) ++b;
    return b;
}

// A word: dof row | time column << row_bits | level << place_bits, the level a two's-complement
// field of 32 - place_bits bits (read back by an arithmetic shift). Coded levels are never 0, so a
// field of 0 is the escape: the level is the window's next exception.
bool fits(std::int32_t level, unsigned place_bits) {
    const std::int64_t half = std::int64_t{1} << (31 - place_bits);
    return level >= -half && level < half;
}

std::uint32_t word_of(std::uint32_t row, std::uint32_t column, std::int32_t level, unsigned row_bits, unsigned place_bits) {
    const std::uint32_t field = fits(level, place_bits) ? static_cast<std::uint32_t>(level) << place_bits : 0u;
    return row | (column << row_bits) | field;
}

// y[row] += (level · step) · v[column] for each word, in the stored order: for every row its terms in
// ascending column, as GroupModel::frame_pose sums the dense grid (its zero terms change no bits).
void accumulate(const std::uint32_t* words, std::size_t count, const std::int32_t* exceptions, unsigned row_bits,
                unsigned place_bits, double step, const double* v, double* y) {
    const std::uint32_t row_mask = (1u << row_bits) - 1;
    const std::uint32_t column_mask = (1u << (place_bits - row_bits)) - 1;
    for (std::size_t k = 0; k < count; ++k) {
        const std::uint32_t w = words[k];
        const std::int32_t field = static_cast<std::int32_t>(w) >> place_bits;
        const std::int32_t level = field != 0 ? field : *exceptions++;
        y[w & row_mask] += static_cast<double>(level) * step * v[(w >> row_bits) & column_mask];
    }
}

}  // namespace

PoseIndex::PoseIndex(const GroupDecoder& decoder) : decoder_(&decoder) {
    const detail::GroupModel& m = *decoder.model_;
    const std::size_t da = std::max<std::size_t>(1, m.active.size());
    const auto W = static_cast<std::size_t>(m.window);
    row_bits_ = bits_for(da);
    place_bits_ = row_bits_ + bits_for(W);
    if (place_bits_ > kMaxPlaceBits)
        throw InvalidArgument("PoseIndex: a group of " + std::to_string(m.active.size()) + " varying dofs and windows of " +
                              std::to_string(W) + " frames has " + std::to_string(da * W) +
                              " coefficients per window; the index holds at most 2^" + std::to_string(kMaxPlaceBits) +
                              " (decode such a group with GroupDecoder)");
    time_rows_.resize(W * W);
    for (std::size_t t = 0; t < W; ++t)
        for (std::size_t c = 0; c < W; ++c) time_rows_[t * W + c] = m.time_basis(static_cast<Eigen::Index>(t), static_cast<Eigen::Index>(c));

    struct Cell {
        std::uint32_t place;  // row + Da · column, the grid's column-major order
        std::int32_t level;
    };
    std::vector<Cell> cells;
    detail::WindowScratch& s = detail::thread_scratch();
    windows_.resize(m.windows.size());
    for (std::size_t i = 0; i < m.windows.size(); ++i) {
        const detail::WindowEntry& e = m.windows[i];
        Window& out = windows_[i];
        out.begin = words_.size();
        out.exceptions = exceptions_.size();
        if (e.step == detail::kRawStep) continue;
        const std::size_t n = decoder.decode_levels(e, s);
        cells.clear();
        for (std::size_t k = 0; k < n; ++k) cells.push_back({m.scan[s.nonzero[k]], s.q[s.nonzero[k]]});
        std::sort(cells.begin(), cells.end(), [](const Cell& a, const Cell& b) { return a.place < b.place; });
        std::uint32_t last_row = 0;
        for (const Cell& c : cells) {
            const auto row = static_cast<std::uint32_t>(c.place % da);
            const auto column = static_cast<std::uint32_t>(c.place / da);
            last_row = std::max(last_row, row);
            words_.push_back(word_of(row, column, c.level, row_bits_, place_bits_));
            if (!fits(c.level, place_bits_)) exceptions_.push_back(c.level);
        }
        out.count = static_cast<std::uint32_t>(n);
        out.rows = n == 0 ? 0 : last_row + 1;  // as GroupModel::dequantize_nonzero
        out.step = detail::step_of(e.step);
    }
    words_.shrink_to_fit();
    exceptions_.shrink_to_fit();
}

std::size_t PoseIndex::memory_bytes() const {
    return words_.capacity() * sizeof(std::uint32_t) + exceptions_.capacity() * sizeof(std::int32_t) + windows_.capacity() * sizeof(Window) +
           time_rows_.capacity() * sizeof(double);
}

const double* PoseIndex::dofs(std::size_t clip, std::size_t global, std::size_t t) const {
    const detail::GroupModel& m = *decoder_->model_;
    const Window& win = windows_[global];
    // A random window is not in cache: its words are requested at once, not a line at a time as the
    // loop reaches them (prefetching is a hint: no effect on the result).
    const auto* first = reinterpret_cast<const char*>(words_.data() + win.begin);
    const std::size_t bytes = win.count * sizeof(std::uint32_t);
    for (std::size_t b = 0; b < bytes; b += 64) __builtin_prefetch(first + b);
    detail::WindowScratch& s = detail::thread_scratch();
    m.prepare(s);
    double* y = s.y.data();
    std::fill(y, y + win.rows, 0.0);
    const double* v = time_rows_.data() + t * static_cast<std::size_t>(m.window);
    accumulate(words_.data() + win.begin, win.count, exceptions_.data() + win.exceptions, row_bits_, place_bits_,
               win.step, v, y);
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
