#pragma once
// Time alignment of a motion set's samples and the D × T × N pose tensor.
#include <optional>
#include <string>
#include <vector>

#include "mocapdb/core/progress.hpp"
#include "mocapdb/dataset/aligned_set.hpp"
#include "mocapdb/dataset/travel_frame.hpp"
#include "mocapdb/motion/clip.hpp"

namespace mocapdb {

/// align_samples refuses more aligned frames than max(4 x the longest sample, this).
constexpr std::size_t kAlignedFramesAlwaysAllowed = 1000;

struct AlignOptions {
    std::string method = "dtw";  ///< "dtw" (against a reference sample) or "linear" (uniform resampling)
    Eigen::Index frames = 100;   ///< T, aligned frames per sample
    /// Reference sample for dtw; default: the sample of median length (ties: the first).
    std::optional<std::size_t> reference;
    /// DTW band: a path may stray this fraction of the length from the diagonal.
    double band = 0.5;
    /// How each sample is turned into its canonical frame: "travel" (its initial direction of
    /// travel along +Z, the first frame's heading for samples that do not travel; travel_frame.hpp)
    /// or "first-frame" (the first frame's heading, canonicalization_of).
    std::string canonical = "travel";
    TravelFrameOptions travel;
    /// Called as samples are done: done counts warps found (one per sample) then pose tensors filled
    /// (one per sample), total = 2 N; item = "warp" or "poses". May be empty.
    ProgressCallback progress;
};

/// Aligns the samples (each already cut to its frame range, all on one skeleton) and builds the
/// tensor. dtw: each sample is warped onto the reference with the pose distance of
/// pose_distance.hpp; the reference timeline is resampled uniformly to T frames. linear: every
/// sample is resampled uniformly to T frames. Pose vectors are interpolated linearly at the warped
/// (fractional) frames; each sample is canonicalized by itself (options.canonical), and exp-map branches are
/// chosen nearest the reference's first pose so they agree across samples. mean/scale are the
/// per-dof mean and standard deviation over all frames and samples (scale 1 where a dof is constant).
AlignedSet align_samples(const std::vector<Clip>& samples, const AlignOptions& options = {});

/// Mean pose distance (cm) between each non-reference sample and the reference over the aligned
/// frames, both taken at their warps (features linearly interpolated): how well the samples agree
/// in time. `samples` as given to align_samples.
double mean_alignment_distance(const std::vector<Clip>& samples, const AlignedSet& aligned);

}  // namespace mocapdb
