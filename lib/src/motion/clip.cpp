#include "mocapdb/motion/clip.hpp"

#include <cmath>

#include "mocapdb/core/error.hpp"

namespace mocapdb {

void validate(const Clip& clip) {
    if (!clip.skeleton) throw InvalidArgument("clip '" + clip.name + "': no skeleton");
    if (!(clip.frame_rate > 0.0 && std::isfinite(clip.frame_rate)))
        throw InvalidArgument("clip '" + clip.name + "': frame rate must be positive and finite");
    if (static_cast<std::size_t>(clip.channels.cols()) != clip.skeleton->channel_count())
        throw InvalidArgument("clip '" + clip.name + "': " + std::to_string(clip.channels.cols()) +
                              " channel columns, the skeleton has " + std::to_string(clip.skeleton->channel_count()));
    if (!clip.channels.allFinite()) throw InvalidArgument("clip '" + clip.name + "': non-finite channel value");
}

Clip slice(const Clip& clip, std::size_t begin, std::size_t end) {
    if (begin >= end || end > clip.frame_count())
        throw InvalidArgument("clip '" + clip.name + "': frame range [" + std::to_string(begin) + ", " +
                              std::to_string(end) + ") is empty or beyond its " + std::to_string(clip.frame_count()) +
                              " frames");
    Clip out;
    out.skeleton = clip.skeleton;
    out.frame_rate = clip.frame_rate;
    out.name = clip.name;
    out.channels = clip.channels.middleRows(static_cast<Eigen::Index>(begin), static_cast<Eigen::Index>(end - begin));
    return out;
}

}  // namespace mocapdb
