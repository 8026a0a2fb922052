#pragma once
// Solver dropouts in captured clips: runs of frames where a joint's rotation channels are exactly 0
// (the joint snaps to its rest pose, e.g. an arm to a T-pose) although the joint moves in the rest of
// the clip. Detected and repaired when samples are taken from a stored clip (set building, eval
// sets); the stored clip itself is never changed, so its lossless tier still reproduces the source.
//
// A maximal run of frames [begin, end) of joint j is a dropout when
//  (1) every rotation channel of j is exactly 0 in each frame of the run, and j has frames where
//      it is not (a joint that never moves has nothing to repair);
//  (2) in each frame of the run, the group of exactly-zero joints around j (parent / children,
//      through joints without rotation channels) borders a joint that is not zero: a whole body at
//      rest is a rest pose, not a dropout;
//  and either
//  (3a) j jumps into the run: at the clean frame before or after it, j's local rotation is at least
//       `min_jump` from the identity (a signal that passes through 0 smoothly is not a dropout), and
//       0 is not the limit of j's range: not every rotation channel's clean values stay on one side
//       of 0 while reaching within `limit_tolerance` of it (a knee pinned straight at its limit by the
//       solver, as CMU's tibiae are in single frames, is a genuine pose);
//  or
//  (3b) the run overlaps a dropout run of an adjacent joint (a whole limb drops out together; its
//       distal joints may sit near 0 anyway, e.g. a wrist).
// On the shared CMU clips this finds the arm / hand / toe dropouts at the start of 16_15, 16_23,
// 16_28, 16_33, 16_54 (and 02_03, 10_04) and none of the single-frame knee or clavicle zeros.
//
// Repair (per run, per joint, rotation channels only): between the clean frames on either side,
// joints with three rotation channels are interpolated by quaternion slerp of the channels' rotation
// (converted back to Euler angles nearest the linearly interpolated, unwrapped angles, so no 2π
// jumps); joints with one or two channels interpolate their angles linearly after unwrapping (exact
// for one axis; the only path two channels can express). A run at the clip's start or end holds the
// nearest clean frame.
//
// Pure functions, no state; safe to call from several threads.
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
