#pragma once
// One motion: a skeleton, a frame rate, and one row of channel values per frame.
#include <memory>
#include <string>

#include "mocapdb/core/types.hpp"
#include "mocapdb/motion/skeleton.hpp"

namespace mocapdb {

struct Clip {
    std::shared_ptr<const Skeleton> skeleton;
    double frame_rate = 120.0;  ///< frames per second
    /// frames by skeleton->channel_count(); positions in cm, rotations in radians.
    FrameMatrix channels;
    std::string name;  ///< where it came from (file stem), informational

    std::size_t frame_count() const noexcept { return static_cast<std::size_t>(channels.rows()); }
    double duration() const noexcept {
        return frame_count() > 0 ? static_cast<double>(frame_count() - 1) / frame_rate : 0.0;
    }
    const double* frame(std::size_t f) const { return channels.row(static_cast<Eigen::Index>(f)).data(); }
};

/// Frames [begin, end) as a clip of their own (same skeleton and rate); InvalidArgument when the
/// range is empty or beyond the clip.
Clip slice(const Clip& clip, std::size_t begin, std::size_t end);

/// Throws InvalidArgument unless the clip has a skeleton, a positive finite frame rate, the right
/// number of columns and only finite values.
void validate(const Clip& clip);

}  // namespace mocapdb
