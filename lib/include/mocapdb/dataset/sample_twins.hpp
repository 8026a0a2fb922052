#pragma once
// Twins in a motion set: samples that show the same frames, which inflate any leave-one-out figure (the
// held-out motion is still in the training set). Two samples are twins when they are cut from one clip
// and share at least TwinOptions::min_shared of the shorter one's frames, or when they come from different
// clips, have the same frame count and every joint (end sites included) of every frame lies within
// tolerance_cm of the other's, both in their canonical placement (first frame's root at the origin,
// facing +Z): e.g. a clip imported twice under two names. Candidates of different clips are found by
// sorting on (frame count, mean first-frame joint height) and comparing only neighbours within the
// tolerance: O(N log N) plus the candidates. Details: docs/evaluation.md (Twins).
#include <functional>
#include <vector>

#include "mocapdb/dataset/motion_set.hpp"
#include "mocapdb/motion/clip.hpp"

namespace mocapdb {

struct TwinOptions {
    double tolerance_cm = 1.0;  ///< different clips: max joint distance at every frame (cm)
    double min_shared = 0.1;    ///< one clip: shared frames / the shorter sample's frames (> 1 frame)
};

struct TwinPair {
    std::size_t a = 0;  ///< sample index, a < b
    std::size_t b = 0;
    bool same_clip = false;         ///< overlapping frame ranges of one clip
    std::size_t shared_frames = 0;  ///< same_clip: frames in both ranges; else the frame count
    double max_distance_cm = 0.0;   ///< different clips: the largest joint distance found
};

struct SampleTwins {
    std::vector<TwinPair> pairs;                   ///< sorted by (a, b)
    std::vector<std::vector<std::size_t>> groups;  ///< connected components of the pairs, ascending
    /// Per sample (N lists): the samples it is a twin of (direct pairs only), ascending.
    std::vector<std::vector<std::size_t>> partners(std::size_t samples) const;
};

/// Frames of sample i (as set_builder's sample_frames gives them). Called in ascending order for the
/// samples whose frame count another clip's sample shares, then again for candidate pairs, so a
/// caller that loads clips lazily should keep the last clip loaded.
using SampleFrames = std::function<Clip(std::size_t index)>;

/// The twins of `set`'s samples; with an empty `frames`, only those of one clip (no frame is read).
/// InvalidArgument when the options are not finite and positive
/// (min_shared in (0, 1]).
SampleTwins find_sample_twins(const MotionSet& set, const SampleFrames& frames, const TwinOptions& options = {});

}  // namespace mocapdb
