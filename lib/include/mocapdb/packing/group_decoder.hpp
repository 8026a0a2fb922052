#pragma once
// Decoding a packed group (packed_group.hpp): any clip, any frame range, one window at a time, or one
// pose by random access. Immutable after construction; every const method is thread-safe (no caches,
// scratch is per call).
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "mocapdb/motion/clip.hpp"

namespace mocapdb::packing {

namespace detail {
struct GroupModel;
struct WindowEntry;
}

class GroupDecoder {
public:
    /// Parses the group's header; throws mocapdb::Error when the bytes are malformed or truncated.
    explicit GroupDecoder(std::vector<std::uint8_t> bytes);
    ~GroupDecoder();
    GroupDecoder(GroupDecoder&&) noexcept;
    GroupDecoder& operator=(GroupDecoder&&) noexcept;

    std::size_t clip_count() const;
    std::size_t frame_count(std::size_t clip) const;
    double frame_rate() const;
    /// Frames per window (W); window w of a clip holds frames [w·W, min((w+1)·W, frames)).
    std::size_t window_length() const;
    std::size_t window_count(std::size_t clip) const;
    /// Coded bytes of the clip's windows (payload only: the header and tables are shared).
    std::size_t clip_payload_bytes(std::size_t clip) const;
    /// The clip's skeleton as decoded (offsets and axes rounded to float32).
    std::shared_ptr<const Skeleton> skeleton(std::size_t clip) const;

    /// Channel rows of one window (rows = its frames). InvalidArgument on a bad index.
    FrameMatrix decode_window(std::size_t clip, std::size_t window) const;
    /// Channel rows of frames [begin, end) (decoded window by window).
    FrameMatrix decode_frames(std::size_t clip, std::size_t begin, std::size_t end) const;
    /// The whole clip (skeleton, rate, every frame).
    Clip decode_clip(std::size_t clip) const;
    /// One frame's channel row into out_row (skeleton(clip)->channel_count() values).
    void decode_pose(std::size_t clip, std::size_t frame, double* out_row) const;

private:
    void check(std::size_t clip) const;
    void raw_rows(const detail::WindowEntry& e, int count, std::size_t channels, FrameMatrix& out) const;
    std::vector<std::uint8_t> bytes_;
    std::unique_ptr<detail::GroupModel> model_;
    std::size_t payload_ = 0;
};

}  // namespace mocapdb::packing
