#pragma once
// Solver dropouts in captured clips: runs of frames where a joint's rotation channels are exactly 0
// (the joint snaps to its rest pose, e.g. an arm to a T-pose) although the joint moves in the rest of
// the clip. Detected and repaired when samples are taken from a stored clip (set building, eval
// sets); the stored clip itself is never changed, so its lossless tier still reproduces the source.
//
// Pure functions, no state; safe to call from several threads.
//
// Details: docs/headers/dataset.md (mocapdb/dataset/dropout_repair.hpp).
#include <string>
#include <vector>

#include "mocapdb/dataset/motion_set.hpp"
#include "mocapdb/motion/clip.hpp"

namespace mocapdb {

struct DropoutOptions {
    double min_jump = 0.017453292519943295;         ///< rad (1°), see (3a)
    double limit_tolerance = 0.017453292519943295;  ///< rad (1°), see (3a)
};

/// One repaired run: joint `joint` (skeleton index; `joint_name` its name) at clip frames [begin, end).
struct DropoutRun {
    std::size_t joint = 0;
    std::string joint_name;
    std::size_t begin = 0;
    std::size_t end = 0;
    double jump = 0.0;  ///< rad: j's rotation angle at the clean frame next to the run (the larger side)
};

/// The dropout runs of `clip`, ordered by joint (skeleton order) then frame. InvalidArgument when the
/// clip is invalid (validate(Clip)).
std::vector<DropoutRun> detect_dropouts(const Clip& clip, const DropoutOptions& options = {});

/// Rewrites the rotation channels of `clip` in every run's frames (see the header). Runs must lie
/// within the clip, name a joint with rotation channels, and leave a frame of that joint outside
/// the run (InvalidArgument otherwise, naming the run). Channels outside the runs are unchanged.
void repair_dropouts(Clip& clip, const std::vector<DropoutRun>& runs);

/// The records a set keeps for a clip's runs (clip id, joint name, frames).
std::vector<RepairedFrames> repair_records(const std::string& clip_id, const std::vector<DropoutRun>& runs);

/// `clip` (stored as `clip_id`) with the set's recorded repairs for it applied (none: unchanged).
/// InvalidArgument when a record names a joint the clip's skeleton lacks or frames beyond the clip.
Clip with_repairs(const Clip& clip, const std::string& clip_id, const std::vector<RepairedFrames>& repairs);

/// "lhumerus, lradius 0-1; lhand 0-6" for the records of one clip (joints with the same frames
/// grouped; frames 0-based, inclusive). Empty when there are none.
std::string describe_repairs(const std::string& clip_id, const std::vector<RepairedFrames>& repairs);

/// The clips with repairs (each once, in record order) and the longest repaired run (frames, end - begin).
struct RepairSummary {
    std::vector<std::string> clips;
    std::size_t longest_run = 0;
};
RepairSummary summarize_repairs(const std::vector<RepairedFrames>& repairs);

}  // namespace mocapdb
