#pragma once
// What the commands working on an aligned set load from a database: the set, its aligned tensor,
// its skeleton and its clips' frame rate.
#include <memory>
#include <string>

#include "mocapdb/dataset/aligned_set.hpp"
#include "mocapdb/dataset/motion_set.hpp"
#include "mocapdb/motion/skeleton.hpp"
#include "mocapdb/store/database.hpp"

namespace mocapdb::cli {

struct SetContext {
    MotionSet set;
    AlignedSet aligned;
    std::shared_ptr<const Skeleton> skeleton;
    double frame_rate = 0.0;        ///< of the first sample's clip
    double seconds_of_motion = 0.0; ///< sum over samples of (frames / frame rate), source timing
    std::uint64_t clip_channel_values = 0;  ///< sum over samples of frames × channels
};

/// InvalidArgument naming the set and the command to run when the set is not aligned.
SetContext load_set_context(const Database& db, const std::string& set);

}  // namespace mocapdb::cli
