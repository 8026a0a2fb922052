#pragma once
// Phase check of an aligned locomotion set: at each aligned frame, do the samples have the same foot
// forward? Whole walks aligned with both ends pinned can put left-foot-forward and right-foot-forward
// poses at one aligned frame (60 % agreement at the ends of walks16), and every blend of
// them is then wrong.
//
// Details: docs/headers/dataset.md (mocapdb/dataset/phase_check.hpp).
#include <string>
#include <utility>
#include <vector>

#include "mocapdb/dataset/aligned_set.hpp"
#include "mocapdb/motion/clip.hpp"

namespace mocapdb {

struct PhaseCheck {
    std::vector<std::string> feet;  ///< left, right
    /// T by N: +1 when sample n has its left foot forward at aligned frame t, −1 right, 0 passing.
    Eigen::MatrixXi forward;
    VecX share;  ///< T: share of samples with the majority's forward foot (0.5 .. 1)
    double min = 0.0, mean = 0.0;

    /// Maximal runs of aligned frames [first, last] (inclusive) with share < threshold.
    std::vector<std::pair<Eigen::Index, Eigen::Index>> below(double threshold) const;
};

/// `samples` as given to align_samples (each cut to its frames, dropouts repaired).
PhaseCheck check_phase(const std::vector<Clip>& samples, const AlignedSet& aligned,
                       const std::vector<std::string>& feet = {}, double passing_cm = 10.0);

}  // namespace mocapdb
