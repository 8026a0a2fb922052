#pragma once
// The gait phase of locomotion from which foot is ahead: the signed distance of the left foot ahead
// of the right along the body's heading. In walking and running it swings between about +-half a
// stride once per gait cycle, so its zero crossings mark the same phase in every clip, whatever the
// speed, turn or capture noise (foot contacts flicker on real data; this signal does not).
#include <string>
#include <vector>

#include "mocapdb/core/types.hpp"
#include "mocapdb/motion/clip.hpp"

namespace mocapdb {

/// Per frame (F): (left foot - right foot) . heading direction, cm; positive when the left foot is
/// ahead. `feet` = {left, right} joint names; empty: default_feet(skeleton). The heading is the motion
/// root's (root_headings). InvalidArgument when a foot is not in the skeleton or none is found.
VecX forward_foot_separation(const Clip& clip, const std::vector<std::string>& feet = {});

/// Frames where the left foot passes the right going forward: the separation changes sign from - to
/// + (the first frame at >= 0), counted only when it swings on to above +threshold after having been
/// below -threshold (hysteresis, so jitter around 0 is no pass). threshold = max(min_swing_cm,
/// 0.3 x the 90th percentile of |separation|). When some pass is confirmed, one is also counted at
/// frame 0 when the clip starts within a frame after one (lead >= 0 and less than the first frame's
/// rise), and at a last crossing the clip ends before confirming, each only where the lead grows at
/// least half as fast as at the confirmed passes. No passes when the feet never swing apart by more
/// than min_swing_cm (standing, jumping with the feet together).
std::vector<std::size_t> left_foot_passes(const VecX& separation, double min_swing_cm = 5.0);

}  // namespace mocapdb
