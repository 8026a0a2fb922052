#pragma once
// `mocapdb align` as a library step: read a stored set's samples (with its dropout
// repairs), time-align them (dataset/alignment.hpp), check that aligned frames agree on the forward
// foot (dataset/phase_check.hpp, legged figures only) and store the D × T × N tensor, committed
// (replacing the set's previous alignment). Nothing is printed.
//
// Errors: InvalidArgument (no such set, a reference label that is not a sample of the set, an unknown
// method), StoreError / IoError from the database; nothing is stored when it throws. The database is
// read before a writer is opened, so errors name the published file. Threads: the database's writer
// lock serializes writers.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "mocapdb/core/progress.hpp"
#include "mocapdb/dataset/aligned_set.hpp"
#include "mocapdb/dataset/phase_check.hpp"

namespace mocapdb::workflow {

struct AlignRequest {
    std::string set;
    Eigen::Index frames = 100;       ///< aligned frames T
    std::string method = "dtw";      ///< AlignOptions::method: dtw | linear
    std::string reference;           ///< sample label ("CLIP" or "CLIP:BEGIN-END"); empty = the library's default
    ProgressCallback read_progress;  ///< per sample read from the database (item: its clip); may be empty
    ProgressCallback progress;       ///< the alignment's (AlignOptions::progress); may be empty
};

struct AlignOutcome {
    AlignedSet aligned;
    std::vector<std::string> labels;  ///< sample labels, in sample order
    double distance = 0.0;            ///< mean pose distance to the reference, cm
    double seconds = 0.0;             ///< wall time of the whole step
    /// Forward-foot agreement per aligned frame; empty when the skeleton's feet are not found (not a
    /// legged figure, or names default_feet does not know).
    std::optional<PhaseCheck> phase;
    /// Every sample starts within a frame of a left-foot pass of its clip (gait_phase.hpp), where the
    /// gait segmentation of set creation cuts: the samples are already cut at one gait phase, so cutting
    /// them that way cannot be the remedy for low phase agreement. False for figures without feet.
    bool cut_at_gait_phase = false;
};

/// Aligns the set's samples and stores the tensor (committed).
AlignOutcome align_set(const std::filesystem::path& db, const AlignRequest& request);

}  // namespace mocapdb::workflow
