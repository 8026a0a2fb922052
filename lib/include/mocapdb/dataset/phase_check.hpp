#pragma once
// Phase check of an aligned locomotion set: at each aligned frame, do the samples have the same foot
// forward? Whole walks aligned with both ends pinned can put left-foot-forward and right-foot-forward
// poses at one aligned frame (issue #15: 60 % agreement at the ends of walks16), and every blend of
// them is then wrong.
//
// At aligned frame t, sample n is read at its warped frame (rounded) and its forward foot is the one
// whose joint lies further along the root's heading ((p_left − p_right) · heading > 0: left). While
// the feet pass each other (less than `passing_cm` apart along the heading) a sample has no forward
// foot and is left out at that frame. The share at t is the larger of the left and right counts over
// the samples that have one (1 when none has). Feet default to default_feet(skeleton)
// (foot_contacts.hpp).
//
// Pure function. InvalidArgument when the samples and the aligned set disagree in count, or the feet
// are not found (callers for non-locomotion sets may skip the check on that error).
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
