#pragma once
// What a viewer draws of a stored clip: the rig (joint names, parents, end sites) and the world
// positions of every joint and end site at each frame (FK, cm, float32), from the source channels or
// from the packed tier (or the clip packed in memory at a chosen E), and the packed copy's error against
// the source at every joint and frame (the metric of `pack` and `report`: FK distance over every joint
// and end site, at the source frames).
// Errors: NotFoundError for an unknown clip, InvalidArgument for an empty or out-of-range frame range,
// StoreError when the database has no packed tier or the clip is not in it. Threads: the Database must
// not be used by another thread meanwhile (HDF5's serial build); the results are plain values.
#include <cstddef>
#include <string>
#include <vector>

#include "mocapdb/motion/clip.hpp"

namespace mocapdb {
class Database;
}

namespace mocapdb::workflow {

struct RigView {
    std::vector<std::string> names;  ///< per joint, end sites included (skeleton order)
    std::vector<int> parents;        ///< per joint, -1 for the root
    std::vector<bool> end_sites;     ///< per joint
};

RigView rig_view(const Skeleton& skeleton);

struct ClipPositions {
    RigView rig;
    double frame_rate = 0.0;
    std::size_t begin = 0;         ///< first frame shown (of the clip)
    std::size_t frames = 0;        ///< frames shown
    std::vector<float> positions;  ///< frames × joints × 3, cm, world frame
};

/// Frames [begin, min(end, clip frames)) of `clip`; InvalidArgument when begin is past the clip.
ClipPositions clip_positions(const Clip& clip, std::size_t begin, std::size_t end);

struct PackedComparison {
    ClipPositions source;
    ClipPositions packed;
    std::vector<float> errors;  ///< frames × joints, cm: |packed - source| per joint and frame
    double max_cm = 0.0;        ///< over the frames shown, every joint and end site
    double rmse_cm = 0.0;
    std::size_t worst_frame = 0;  ///< of the clip
    std::string worst_joint;
    double tier_max_error_cm = 0.0;  ///< the bound the tier was packed to
};

/// The clip's frames [begin, end) from its source channels and from the packed tier.
PackedComparison compare_with_packed(const Database& db, const std::string& clip, std::size_t begin, std::size_t end);

/// The same with the whole clip packed alone, in memory, at max_error_cm (> 0, finite; InvalidArgument
/// otherwise), as `pack` packs a group (packing::pack_measured); nothing is written.
PackedComparison compare_with_packed_at(const Clip& source, double max_error_cm, std::size_t begin, std::size_t end);

}  // namespace mocapdb::workflow
