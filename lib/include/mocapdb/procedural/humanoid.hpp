#pragma once
// The built-in humanoid skeleton the procedural generators animate: 170 cm tall, Y up, facing +Z,
// rest pose a T-pose (arms along ±X, palms down, legs straight, feet flat and pointing +Z).
//
// Hierarchy (joint names follow the common BVH/Mixamo naming so that Blender and the project's foot
// detection (default_feet: "LeftToeBase", "RightToeBase") recognize them):
//   Hips (root: Xposition Yposition Zposition Yrotation Xrotation Zrotation, heading outermost)
//     Spine - Spine1 - Spine2 - Neck - Head - Head_end
//     Spine2 - LeftShoulder (clavicle) - LeftArm - LeftForeArm - LeftHand - LeftHand_end   (and Right*)
//     Hips - LeftUpLeg - LeftLeg - LeftFoot - LeftToeBase - LeftToeBase_end                 (and Right*)
// Every other joint has three rotation channels (arms, clavicles, spine, neck, head: Z X Y; legs: Z Y X,
// so that the middle, gimbal-limited angle is the bone's twist). End sites are named PARENT_end, as
// the BVH reader names them, so a written and re-read skeleton compares equal (same_structure).
//
// Rest geometry (cm, floor at y = 0): hips 95, hip joints at (±9, 91, 0), knees 49, ankles 8, balls of
// the feet (toe bases) at (±9, 1, 13), toe tips 19 cm ahead of the ankle; spine 104/116/128, neck 143,
// head 152, top of the head 170; shoulder joints at (±17, 140, 0); upper arm 28, forearm 25, hand 18.
#include <memory>
#include <string>
#include <vector>

#include "mocapdb/core/types.hpp"
#include "mocapdb/motion/skeleton.hpp"

namespace mocapdb::procedural {

/// Joint names of the humanoid, for callers that address joints (extractors, tests).
struct HumanoidNames {
    static constexpr const char* root = "Hips";
    static constexpr const char* head_end = "Head_end";
    static constexpr const char* right_hand_end = "RightHand_end";  ///< the reaching end effector
    static constexpr const char* left_toe = "LeftToeBase";           ///< foot contact joints
    static constexpr const char* right_toe = "RightToeBase";
};

/// The skeleton (built once, shared; immutable). Source units: cm, degrees.
std::shared_ptr<const Skeleton> humanoid_skeleton();

/// {"LeftToeBase", "RightToeBase"}: the joints the foot-contact detection should use.
std::vector<std::string> humanoid_feet();

/// The heel's ground point in the foot (ankle) joint's frame, cm: the pivot of heel strike. The ball
/// of the foot is the toe-base joint itself.
Vec3 humanoid_heel_point();

}  // namespace mocapdb::procedural
