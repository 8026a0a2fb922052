#include "mocapdb/packing/group_decoder.hpp"

#include <algorithm>
#include <cstring>
#include <string>

#include "mocapdb/packing/runtime_decoder.hpp"
#include "group_model.hpp"

namespace mocapdb::packing {

using detail::thread_scratch;

GroupDecoder::GroupDecoder(std::vector<std::uint8_t> bytes)
    : bytes_(std::move(bytes)), model_(std::make_unique<detail::GroupModel>()) {
    payload_ = model_->read_header(bytes_.data(), bytes_.size());
    if (!model_->skeletons.empty()) channels_ = model_->skeletons.front().skeleton->channel_count();
    if (model_->runtime && !model_->clips.empty()) {
        // The runtime decoder views bytes_ (its heap buffer stays put when the decoder moves) and
        // parses the header itself: this model is not kept.
        runtime_ = std::make_unique<RuntimeDecoder>(bytes_.data(), bytes_.size());
        model_.reset();
        return;
    }
    // The classes depend only on the step: worked out once per step in use, not per decode.
    classes_.resize(detail::kMaxStep + 1);
    for (const detail::WindowEntry& e : model_->windows)
        if (e.step != detail::kRawStep && classes_[e.step].empty())
            position_classes(model_->levels, detail::step_of(e.step), classes_[e.step]);
}
GroupDecoder::~GroupDecoder() = default;
GroupDecoder::GroupDecoder(GroupDecoder&&) noexcept = default;
GroupDecoder& GroupDecoder::operator=(GroupDecoder&&) noexcept = default;

PackFormat GroupDecoder::format() const {
    return runtime_ || model_->runtime ? PackFormat::Runtime : PackFormat::Archive;
}
std::size_t GroupDecoder::clip_count() const { return runtime_ ? runtime_->clip_count() : model_->clips.size(); }
double GroupDecoder::frame_rate() const { return runtime_ ? runtime_->frame_rate() : model_->frame_rate; }
std::size_t GroupDecoder::window_length() const {
    return runtime_ ? runtime_->window_length() : static_cast<std::size_t>(model_->window);
}

void GroupDecoder::check(std::size_t clip) const {
    if (clip >= clip_count())
        throw InvalidArgument("GroupDecoder: clip " + std::to_string(clip) + " of " + std::to_string(clip_count()));
}

void GroupDecoder::check(std::size_t clip, std::size_t frame) const {
    if (frame >= frame_count(clip))
        throw InvalidArgument("GroupDecoder: frame " + std::to_string(frame) + " of " +
                              std::to_string(frame_count(clip)));
}

std::size_t GroupDecoder::frame_count(std::size_t clip) const {
    check(clip);
    return runtime_ ? runtime_->frame_count(clip) : model_->clips[clip].frames;
}

std::size_t GroupDecoder::window_count(std::size_t clip) const {
    return (frame_count(clip) + window_length() - 1) / window_length();
}

std::size_t GroupDecoder::clip_payload_bytes(std::size_t clip) const {
    if (runtime_) return runtime_->clip_bytes(clip);
    const std::size_t first = static_cast<std::size_t>(model_->clips.at(clip).first_window);
    std::size_t total = 0;
    for (std::size_t w = 0, n = window_count(clip); w < n; ++w) total += model_->windows.at(first + w).size;
    return total;
}

std::size_t GroupDecoder::resident_bytes() const {
    if (runtime_) return sizeof(RuntimeDecoder) + runtime_->resident_bytes();
    const detail::GroupModel& m = *model_;
    std::size_t total = sizeof(detail::GroupModel);
    total += m.extra_columns.capacity() * sizeof(int) + m.active.capacity() * sizeof(int) +
             m.constant.capacity() * sizeof(double);
    total += static_cast<std::size_t>(m.dof_basis.size() + m.time_basis.size()) * sizeof(double);
    total += (m.dof_energy.capacity() + m.time_energy.capacity() + m.sigma.capacity()) * sizeof(float) +
             m.scan.capacity() * sizeof(std::uint32_t) + m.scan_row.capacity() * sizeof(std::uint16_t) +
             m.levels.capacity() * sizeof(double);
    total += m.clips.capacity() * sizeof(detail::ClipEntry) + m.windows.capacity() * sizeof(detail::WindowEntry);
    for (const detail::SkeletonEntry& e : m.skeletons) {
        total += sizeof(e) + sizeof(Skeleton) + e.skeleton->size() * sizeof(Joint) +
                 static_cast<std::size_t>(e.weights.size()) * sizeof(double) +
                 e.active_weights.capacity() * sizeof(double) + e.stored_axes.capacity() * sizeof(e.stored_axes[0]) +
                 e.writer.memory_bytes();
        for (const Joint& j : e.skeleton->joints())
            total += j.name.capacity() + j.channels.capacity() * sizeof(ChannelType);
    }
    for (const auto& c : classes_) total += c.capacity();
    // One thread's scratch, as prepare() sizes it.
    const std::size_t da = m.active.size(), cells = da * static_cast<std::size_t>(m.window);
    total += cells * (sizeof(std::int32_t) + sizeof(std::uint8_t) + sizeof(std::uint32_t) + sizeof(double)) +
             da * (2 + 2 * detail::kFrameBlock) * sizeof(double) + static_cast<std::size_t>(m.dofs) * sizeof(double) +
             sizeof(detail::WindowScratch);
    return total;
}

std::shared_ptr<const Skeleton> GroupDecoder::skeleton(std::size_t clip) const {
    check(clip);
    if (runtime_) return runtime_->skeleton(clip);
    return model_->skeletons[model_->clips[clip].skeleton].skeleton;
}

const detail::WindowEntry& GroupDecoder::entry(std::size_t clip, std::size_t window) const {
    return model_->windows[model_->clips[clip].first_window + window];
}

int GroupDecoder::frames_in(std::size_t clip, std::size_t window) const {
    const std::uint64_t W = window_length();
    return static_cast<int>(std::min<std::uint64_t>(W, model_->clips[clip].frames - window * W));
}

void GroupDecoder::raw_rows(const detail::WindowEntry& e, int frames, std::size_t channels, int t0, int count,
                            double* out) const {
    const std::size_t values = static_cast<std::size_t>(frames) * channels;
    if (e.size != values * sizeof(double))
        throw Error("packed group: raw window of " + std::to_string(e.size) + " bytes, expected " +
                    std::to_string(values * sizeof(double)));
    std::memcpy(out, bytes_.data() + payload_ + e.offset + static_cast<std::size_t>(t0) * channels * sizeof(double),
                static_cast<std::size_t>(count) * channels * sizeof(double));
}

std::size_t GroupDecoder::decode_levels(const detail::WindowEntry& e, detail::WindowScratch& s) const {
    const detail::GroupModel& m = *model_;
    m.prepare(s);
    const std::vector<std::uint8_t>& classes = classes_[e.step];
    s.contexts = m.contexts;  // every window starts from the trained probabilities
    std::size_t nonzeros = 0;
    decode_coefficients(bytes_.data() + payload_ + e.offset, e.size, classes.data(), classes.size(), m.grid(),
                        s.contexts, s.q.data(), s.level.data(), s.nonzero.data(), &nonzeros);
    return nonzeros;
}

void GroupDecoder::load_window(const detail::WindowEntry& e, detail::WindowScratch& s) const {
    const std::size_t nonzeros = decode_levels(e, s);
    // Only the nonzero coefficients are dequantized (no passes over the zeros of the grid).
    model_->dequantize_nonzero(e.step, s.q.data(), s.nonzero.data(), nonzeros, s);
}

FrameMatrix GroupDecoder::decode_window(std::size_t clip, std::size_t window) const {
    if (window >= window_count(clip))
        throw InvalidArgument("GroupDecoder: window " + std::to_string(window) + " of " +
                              std::to_string(window_count(clip)));
    if (runtime_) {
        const std::size_t W = window_length();
        return runtime_->decode_frames(clip, window * W, std::min(frame_count(clip), (window + 1) * W));
    }
    const detail::WindowEntry& e = entry(clip, window);
    const int count = frames_in(clip, window);
    FrameMatrix rows(count, static_cast<Eigen::Index>(channels_));
    if (e.step == detail::kRawStep) {
        raw_rows(e, count, channels_, 0, count, rows.data());
        return rows;
    }
    detail::WindowScratch& s = thread_scratch();
    load_window(e, s);
    for (int t = 0; t < count; ++t)
        model_->frame_row(model_->clips[clip], s.g.data(), s.columns, s.rows, t, s, rows.row(t).data());
    return rows;
}

FrameMatrix GroupDecoder::decode_frames(std::size_t clip, std::size_t begin, std::size_t end) const {
    check(clip);
    if (begin > end || end > frame_count(clip))
        throw InvalidArgument("GroupDecoder: frames [" + std::to_string(begin) + ", " + std::to_string(end) +
                              ") outside [0, " + std::to_string(frame_count(clip)) + ")");
    if (runtime_) return runtime_->decode_frames(clip, begin, end);
    FrameMatrix out(static_cast<Eigen::Index>(end - begin), static_cast<Eigen::Index>(channels_));
    const std::size_t W = window_length();
    for (std::size_t w = begin / W; w * W < end; ++w) {
        const FrameMatrix rows = decode_window(clip, w);
        const std::size_t lo = std::max(begin, w * W);
        const std::size_t hi = std::min(end, w * W + static_cast<std::size_t>(rows.rows()));
        out.middleRows(static_cast<Eigen::Index>(lo - begin), static_cast<Eigen::Index>(hi - lo)) =
            rows.middleRows(static_cast<Eigen::Index>(lo - w * W), static_cast<Eigen::Index>(hi - lo));
    }
    return out;
}

Clip GroupDecoder::decode_clip(std::size_t clip) const {
    Clip out;
    out.skeleton = skeleton(clip);
    out.frame_rate = frame_rate();
    out.channels = decode_frames(clip, 0, frame_count(clip));
    return out;
}

void GroupDecoder::decode_pose(std::size_t clip, std::size_t frame, double* out_row) const {
    if (runtime_) return runtime_->decode_pose(clip, frame, out_row);
    check(clip, frame);
    const std::size_t W = window_length();
    const std::size_t w = frame / W;
    const int t = static_cast<int>(frame % W);
    const detail::WindowEntry& e = entry(clip, w);
    if (e.step == detail::kRawStep) {
        raw_rows(e, frames_in(clip, w), channels_, t, 1, out_row);
        return;
    }
    detail::WindowScratch& s = thread_scratch();
    load_window(e, s);
    model_->frame_row(model_->clips[clip], s.g.data(), s.columns, s.rows, t, s, out_row);
}

void GroupDecoder::decode_local_pose(std::size_t clip, std::size_t frame, LocalPose& out) const {
    if (runtime_) return runtime_->decode_local_pose(clip, frame, out);
    check(clip, frame);
    const std::size_t W = window_length();
    const std::size_t w = frame / W;
    const int t = static_cast<int>(frame % W);
    const detail::WindowEntry& e = entry(clip, w);
    detail::WindowScratch& s = thread_scratch();
    const detail::ClipEntry& c = model_->clips[clip];
    if (e.step == detail::kRawStep) {
        model_->prepare(s);
        s.row.resize(channels_);
        raw_rows(e, frames_in(clip, w), channels_, t, 1, s.row.data());
        model_->local_of_row(c, s.row.data(), out);
        return;
    }
    load_window(e, s);
    model_->frame_pose(c, s.g.data(), s.columns, s.rows, t, s, s.p.data());
    model_->local_of(c, s.p.data(), out);
}

}  // namespace mocapdb::packing
