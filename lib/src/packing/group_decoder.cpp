#include "mocapdb/packing/group_decoder.hpp"

#include <algorithm>
#include <cstring>
#include <string>

#include "group_model.hpp"

namespace mocapdb::packing {

GroupDecoder::GroupDecoder(std::vector<std::uint8_t> bytes)
    : bytes_(std::move(bytes)), model_(std::make_unique<detail::GroupModel>()) {
    payload_ = model_->read_header(bytes_.data(), bytes_.size());
}
GroupDecoder::~GroupDecoder() = default;
GroupDecoder::GroupDecoder(GroupDecoder&&) noexcept = default;
GroupDecoder& GroupDecoder::operator=(GroupDecoder&&) noexcept = default;

std::size_t GroupDecoder::clip_count() const { return model_->clips.size(); }
double GroupDecoder::frame_rate() const { return model_->frame_rate; }
std::size_t GroupDecoder::window_length() const { return static_cast<std::size_t>(model_->window); }

void GroupDecoder::check(std::size_t clip) const {
    if (clip >= model_->clips.size())
        throw InvalidArgument("GroupDecoder: clip " + std::to_string(clip) + " of " + std::to_string(model_->clips.size()));
}

std::size_t GroupDecoder::frame_count(std::size_t clip) const {
    check(clip);
    return model_->clips[clip].frames;
}

std::size_t GroupDecoder::window_count(std::size_t clip) const {
    check(clip);
    return (model_->clips[clip].frames + window_length() - 1) / window_length();
}

std::size_t GroupDecoder::clip_payload_bytes(std::size_t clip) const {
    const std::size_t first = static_cast<std::size_t>(model_->clips.at(clip).first_window);
    std::size_t total = 0;
    for (std::size_t w = 0, n = window_count(clip); w < n; ++w) total += model_->windows.at(first + w).size;
    return total;
}

std::shared_ptr<const Skeleton> GroupDecoder::skeleton(std::size_t clip) const {
    check(clip);
    return model_->skeletons[model_->clips[clip].skeleton].skeleton;
}

namespace {
void decode_q(const detail::GroupModel& m, const std::uint8_t* payload, const detail::WindowEntry& e,
              std::vector<std::int32_t>& out_q) {
    std::vector<std::uint8_t> classes;
    position_classes(m.levels, detail::step_of(e.step), classes);
    decode_coefficients(payload + e.offset, e.size, classes, m.grid(), m.contexts, out_q);
}
}  // namespace

void GroupDecoder::raw_rows(const detail::WindowEntry& e, int count, std::size_t channels, FrameMatrix& out) const {
    const std::size_t values = static_cast<std::size_t>(count) * channels;
    if (e.size != values * sizeof(double))
        throw Error("packed group: raw window of " + std::to_string(e.size) + " bytes, expected " +
                    std::to_string(values * sizeof(double)));
    out.resize(count, static_cast<Eigen::Index>(channels));
    std::memcpy(out.data(), bytes_.data() + payload_ + e.offset, values * sizeof(double));
}

FrameMatrix GroupDecoder::decode_window(std::size_t clip, std::size_t window) const {
    if (window >= window_count(clip))
        throw InvalidArgument("GroupDecoder: window " + std::to_string(window) + " of " +
                              std::to_string(window_count(clip)));
    const detail::ClipEntry& c = model_->clips[clip];
    const detail::WindowEntry& e = model_->windows[c.first_window + window];
    const auto count = static_cast<int>(std::min<std::uint64_t>(window_length(), c.frames - window * window_length()));
    FrameMatrix rows;
    if (e.step == detail::kRawStep) {
        raw_rows(e, count, skeleton(clip)->channel_count(), rows);
        return rows;
    }
    std::vector<std::int32_t> q;
    decode_q(*model_, bytes_.data() + payload_, e, q);
    model_->reconstruct(c, e.step, q, count, rows);
    return rows;
}

FrameMatrix GroupDecoder::decode_frames(std::size_t clip, std::size_t begin, std::size_t end) const {
    check(clip);
    if (begin > end || end > frame_count(clip))
        throw InvalidArgument("GroupDecoder: frames [" + std::to_string(begin) + ", " + std::to_string(end) +
                              ") outside [0, " + std::to_string(frame_count(clip)) + ")");
    const auto channels = static_cast<Eigen::Index>(skeleton(clip)->channel_count());
    FrameMatrix out(static_cast<Eigen::Index>(end - begin), channels);
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
    if (frame >= frame_count(clip))
        throw InvalidArgument("GroupDecoder: frame " + std::to_string(frame) + " of " + std::to_string(frame_count(clip)));
    const detail::ClipEntry& c = model_->clips[clip];
    const std::size_t W = window_length();
    const detail::WindowEntry& e = model_->windows[c.first_window + frame / W];
    if (e.step == detail::kRawStep) {
        FrameMatrix rows;
        const auto count = static_cast<int>(std::min<std::uint64_t>(W, c.frames - (frame / W) * W));
        raw_rows(e, count, skeleton(clip)->channel_count(), rows);
        std::copy(rows.row(static_cast<Eigen::Index>(frame % W)).data(),
                  rows.row(static_cast<Eigen::Index>(frame % W)).data() + rows.cols(), out_row);
        return;
    }
    std::vector<std::int32_t> q;
    decode_q(*model_, bytes_.data() + payload_, e, q);
    model_->reconstruct_frame(c, e.step, q, static_cast<int>(frame % W), out_row);
}

}  // namespace mocapdb::packing
