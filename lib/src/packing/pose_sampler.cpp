#include "mocapdb/packing/pose_sampler.hpp"

#include <algorithm>
#include <limits>

#include "mocapdb/packing/runtime_decoder.hpp"
#include "group_model.hpp"

namespace mocapdb::packing {

struct PoseSampler::Slot {
    std::uint64_t window = std::numeric_limits<std::uint64_t>::max();  ///< index in the group, or none
    std::size_t clip = 0;
    std::vector<double> g;  ///< dequantized coefficients (coded windows)
    int columns = 0;
    int dof_rows = 0;                 ///< rows of g up to its last nonzero one
    std::vector<double> rows;         ///< W rows of channels, row-major
    std::vector<std::uint8_t> done;   ///< per frame: rows holds it
    std::vector<double> poses;        ///< W frames of dofs (D each), coded windows
    std::vector<std::uint8_t> posed;  ///< per frame: poses holds it
    std::uint64_t used = 0;           ///< tick of the last request (least recently used is evicted)
    bool raw = false;                 ///< a raw window: rows hold every frame, poses nothing
    /// Runtime groups: the window's rows and local poses, each decoded whole on first use.
    std::vector<LocalPose> locals;
    bool rows_ready = false, locals_ready = false;
};

PoseSampler::PoseSampler(const GroupDecoder& decoder, std::size_t capacity)
    : decoder_(&decoder), channels_(decoder.channels_), scratch_(std::make_unique<detail::WindowScratch>()) {
    if (capacity == 0) throw InvalidArgument("PoseSampler: capacity must be at least 1 window");
    std::uint64_t windows = 0;
    for (std::size_t c = 0; c < decoder.clip_count(); ++c) {
        first_window_.push_back(windows);
        windows += decoder.window_count(c);
    }
    slot_of_.assign(windows, -1);
    slots_.resize(capacity);
    if (decoder.runtime_) {
        for (Slot& s : slots_) s.rows.resize(decoder.window_length() * channels_);
        return;
    }
    const detail::GroupModel& m = *decoder.model_;
    m.prepare(*scratch_);
    const auto W = static_cast<std::size_t>(m.window);
    for (Slot& s : slots_) {
        s.g.resize(scratch_->g.size());
        s.rows.resize(W * channels_);
        s.done.assign(W, 0);
        s.poses.resize(W * static_cast<std::size_t>(m.dofs));
        s.posed.assign(W, 0);
    }
}

PoseSampler::~PoseSampler() = default;
PoseSampler::PoseSampler(PoseSampler&&) noexcept = default;
PoseSampler& PoseSampler::operator=(PoseSampler&&) noexcept = default;

std::size_t PoseSampler::capacity() const { return slots_.size(); }

void PoseSampler::clear() {
    for (Slot& s : slots_) {
        if (s.window != std::numeric_limits<std::uint64_t>::max()) slot_of_[s.window] = -1;
        s.window = std::numeric_limits<std::uint64_t>::max();
        s.used = 0;
    }
    hits_ = misses_ = 0;
}

std::size_t PoseSampler::fill(std::size_t clip, std::size_t window, std::uint64_t global) {
    // Least recently used slot (a linear scan: cheap beside the range decoding that follows).
    std::size_t victim = 0;
    for (std::size_t i = 1; i < slots_.size(); ++i)
        if (slots_[i].used < slots_[victim].used) victim = i;
    Slot& s = slots_[victim];
    if (s.window != std::numeric_limits<std::uint64_t>::max()) slot_of_[s.window] = -1;
    s.window = std::numeric_limits<std::uint64_t>::max();  // stays empty should decoding throw
    std::fill(s.done.begin(), s.done.end(), std::uint8_t(0));
    std::fill(s.posed.begin(), s.posed.end(), std::uint8_t(0));
    if (decoder_->runtime_) {
        s.rows_ready = s.locals_ready = false;  // decoded when first asked for
        s.raw = false;
    } else if (const detail::WindowEntry& e = decoder_->entry(clip, window); e.step == detail::kRawStep) {
        const int frames = decoder_->frames_in(clip, window);
        decoder_->raw_rows(e, frames, channels_, 0, frames, s.rows.data());
        std::fill(s.done.begin(), s.done.begin() + frames, std::uint8_t(1));
        s.raw = true;
    } else {
        s.raw = false;
        decoder_->load_window(e, *scratch_);
        s.g.swap(scratch_->g);  // same size: no allocation, the scratch takes the old buffer
        s.columns = scratch_->columns;
        s.dof_rows = scratch_->rows;
    }
    s.window = global;
    s.clip = clip;
    slot_of_[global] = static_cast<std::int32_t>(victim);
    return victim;
}

PoseSampler::Slot& PoseSampler::slot(std::size_t clip, std::size_t frame) {
    decoder_->check(clip, frame);
    const std::size_t window = frame / decoder_->window_length();
    const std::uint64_t global = first_window_[clip] + window;
    std::int32_t index = slot_of_[global];
    if (index < 0) {
        index = static_cast<std::int32_t>(fill(clip, window, global));
        ++misses_;
    } else {
        ++hits_;
    }
    Slot& s = slots_[static_cast<std::size_t>(index)];
    s.used = ++tick_;
    return s;
}

const double* PoseSampler::dofs(Slot& s, std::size_t clip, std::size_t t) {
    const detail::GroupModel& m = *decoder_->model_;
    double* p = s.poses.data() + t * static_cast<std::size_t>(m.dofs);
    if (!s.posed[t]) {
        const auto W = static_cast<std::size_t>(m.window);
        const auto B = static_cast<std::size_t>(detail::kFrameBlock);
        // Sequential access (the previous frame was asked for): the rest of the window, kFrameBlock
        // frames at a time while they fit (cheaper per frame, and the window's coefficients are read
        // while still in cache: in a crowd, other clips' windows evict them between this clip's
        // frames); otherwise (random access, frame skipping) this frame alone.
        const bool sequential = t > 0 && s.posed[t - 1];
        std::size_t u = t;
        for (; sequential && u + B <= W && !s.posed[u]; u += B) {
            if (std::find(&s.posed[u], &s.posed[u] + B, 1) != &s.posed[u] + B) break;
            m.frames_pose(m.clips[clip], s.g.data(), s.columns, s.dof_rows, static_cast<int>(u), *scratch_,
                          s.poses.data() + u * static_cast<std::size_t>(m.dofs));
            std::fill(&s.posed[u], &s.posed[u] + B, std::uint8_t(1));
        }
        if (u == t) {
            m.frame_pose(m.clips[clip], s.g.data(), s.columns, s.dof_rows, static_cast<int>(t), *scratch_, p);
            s.posed[t] = 1;
        }
    }
    return p;
}

const double* PoseSampler::pose(std::size_t clip, std::size_t frame) {
    Slot& s = slot(clip, frame);
    if (decoder_->runtime_) {
        const std::size_t W = decoder_->window_length(), first = frame / W * W;
        if (!s.rows_ready) {
            const FrameMatrix rows =
                decoder_->runtime_->decode_frames(clip, first, std::min(first + W, decoder_->frame_count(clip)));
            std::copy(rows.data(), rows.data() + rows.size(), s.rows.data());
            s.rows_ready = true;
        }
        return s.rows.data() + (frame - first) * channels_;
    }
    const detail::GroupModel& m = *decoder_->model_;
    const std::size_t t = frame % static_cast<std::size_t>(m.window);
    double* row = s.rows.data() + t * channels_;
    if (!s.done[t]) {
        m.row_of(m.clips[clip], dofs(s, clip, t), row);
        s.done[t] = 1;
    }
    return row;
}

void PoseSampler::local_pose(std::size_t clip, std::size_t frame, LocalPose& out) {
    Slot& s = slot(clip, frame);
    if (decoder_->runtime_) {
        const std::size_t W = decoder_->window_length(), first = frame / W * W;
        if (!s.locals_ready) {
            decoder_->runtime_->decode_local_poses(clip, first, std::min(first + W, decoder_->frame_count(clip)),
                                                   s.locals);
            s.locals_ready = true;
        }
        const LocalPose& p = s.locals[frame - first];
        out.rotations.assign(p.rotations.begin(), p.rotations.end());
        out.translations.assign(p.translations.begin(), p.translations.end());
        return;
    }
    const detail::GroupModel& m = *decoder_->model_;
    const std::size_t t = frame % static_cast<std::size_t>(m.window);
    if (s.raw) m.local_of_row(m.clips[clip], s.rows.data() + t * channels_, out);
    else m.local_of(m.clips[clip], dofs(s, clip, t), out);
}

void PoseSampler::pose(std::size_t clip, std::size_t frame, double* out_row) {
    const double* row = pose(clip, frame);
    std::copy(row, row + channels_, out_row);
}

}  // namespace mocapdb::packing
