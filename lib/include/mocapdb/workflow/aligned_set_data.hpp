#pragma once
// What the steps working on an aligned set load from a database: the set, its aligned
// tensor, its skeleton and frame rate (those of the first sample's clip), and the size of the source
// motion the set covers (what the rate report compares against). Used by compression, the rate
// report, the naive synthesis model (load_model.hpp) and `mocapdb export`. The compressed synthesis
// model loads less (AlignedTimingData: the warps and the tensor's shape, not its values).
// Errors: InvalidArgument naming the set and the command to run when the set is not aligned, or
// naming a sample's clip missing from the database; StoreError / IoError from the database.
// Thread safety: the Database must not be written meanwhile; the result is a plain value.
#include <cstdint>
#include <memory>
#include <string>

#include "mocapdb/dataset/aligned_set.hpp"
#include "mocapdb/dataset/aligned_timing.hpp"
#include "mocapdb/dataset/motion_set.hpp"
#include "mocapdb/motion/skeleton.hpp"

namespace mocapdb {
class Database;
}

namespace mocapdb::workflow {

struct AlignedSetData {
    MotionSet set;
    AlignedSet aligned;
    std::shared_ptr<const Skeleton> skeleton;
    double frame_rate = 0.0;                ///< of the first sample's clip
    double seconds_of_motion = 0.0;         ///< sum over samples of (frames / frame rate), source timing
    std::uint64_t clip_channel_values = 0;  ///< sum over samples of frames × channels
};

AlignedSetData load_aligned_set(const Database& db, const std::string& set);

/// The set, its aligned form's timing and shape (Database::load_aligned_timing: the tensor's values
/// are not read), skeleton and frame rate; the same checks and errors as load_aligned_set.
struct AlignedTimingData {
    MotionSet set;
    AlignedTiming timing;
    std::shared_ptr<const Skeleton> skeleton;
    double frame_rate = 0.0;  ///< of the first sample's clip
};

AlignedTimingData load_aligned_timing(const Database& db, const std::string& set);

}  // namespace mocapdb::workflow
