#pragma once
// Back from aligned time to a sample's own timing: the inverse of the alignment's resampling.
#include <memory>
#include <string>

#include "mocapdb/core/types.hpp"
#include "mocapdb/motion/clip.hpp"
#include "mocapdb/motion/pose_vector.hpp"

namespace mocapdb {

/// Pose vectors at the sample's own frames 0 .. frames − 1. aligned: D × T poses at aligned frames;
/// warp: T entries, strictly increasing, warp(t) = the sample frame shown at aligned frame t (an
/// AlignedSet warps column). Each output frame f is placed at the aligned time where the
/// piecewise-linear warp reaches f, and its pose interpolated linearly between the two aligned
/// frames around it (frames outside [warp(0), warp(T − 1)] take the end poses). Returns D × frames.
/// Throws InvalidArgument on mismatched sizes, a warp that does not increase, or frames < 1.
MatX poses_at_sample_frames(const Eigen::Ref<const MatX>& aligned, const Eigen::Ref<const VecX>& warp,
                            Eigen::Index frames);

/// A clip from pose vectors (D × F, canonical frame) placed back in the world by `canonical`.
Clip clip_from_pose_vectors(std::shared_ptr<const Skeleton> skeleton, const Eigen::Ref<const MatX>& poses,
                            const Canonicalization& canonical, double frame_rate, std::string name);

}  // namespace mocapdb
