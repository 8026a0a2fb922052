#pragma once
// Procedural reaching: the humanoid turns toward a target, reaches it with the right hand (analytic
// two-bone IK on shoulder-elbow-wrist), holds, and returns to its rest stance. Feet stay planted
// (leg IK keeps them fixed while the pelvis turns, shifts and crouches); the torso twists and bends,
// the head looks at the target ahead of the hand, the left arm hangs under gravity.
//
// Details: docs/headers/procedural.md (mocapdb/procedural/reach.hpp).
#include <cstddef>
#include <optional>

#include "mocapdb/core/types.hpp"
#include "mocapdb/motion/clip.hpp"

namespace mocapdb::procedural {

struct ReachParams {
    double angle_deg = 0.0;         ///< bearing of the target around the body, degrees (+ = left)
    double height_cm = 110.0;       ///< target height above the floor, cm
    double distance_cm = 55.0;      ///< horizontal distance of the target from the body's axis, cm
    double elbow_swivel_deg = 0.0;  ///< rotates the elbow about the shoulder→wrist axis (+ = elbow up/out)
};

struct ReachOptions {
    double frame_rate = 60.0;      ///< Hz
    double lead_in_s = 0.25;       ///< standing still before the reach starts
    double hold_s = 0.35;          ///< hand held on the target
    double lead_out_s = 0.25;      ///< standing still after the return
    double target_width_cm = 4.0;  ///< W of Fitts' law
    double return_ratio = 0.85;    ///< return duration / reach duration
};

struct ReachMotion {
    Clip clip;                      ///< humanoid_skeleton(), name "reach"
    Vec3 target = Vec3::Zero();     ///< world position of the target, cm
    std::size_t reach_begin = 0;    ///< first frame of the reaching movement
    std::size_t contact_frame = 0;  ///< first frame with the hand on the target
    std::size_t release_frame = 0;  ///< last frame with the hand on the target
    double reach_seconds = 0.0;     ///< duration of the reaching movement
    double body_turn = 0.0;         ///< how far the body (chest) turns toward the target, radians
    double lean = 0.0;              ///< how far the body bends and crouches, 0…1
};

/// The world position of the target of `params` (cm). InvalidArgument outside the ranges above.
Vec3 reach_target(const ReachParams& params);

/// Generates the reach. Deterministic. InvalidArgument for out-of-range or unreachable targets.
ReachMotion generate_reach(const ReachParams& params, const ReachOptions& options = {});

/// Where a reach (generated or synthesized) holds: the world position (cm) of the humanoid's right
/// hand end site at the slowest frame among those where it is at least 80 % of its largest distance
/// from where it started. nullopt when the skeleton has no such end site or the clip has fewer than
/// 3 frames.
std::optional<Vec3> reach_hold_point(const Clip& clip);

}  // namespace mocapdb::procedural
