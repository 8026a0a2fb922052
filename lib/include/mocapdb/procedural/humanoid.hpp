#pragma once
// The built-in humanoid skeleton the procedural generators animate: 170 cm tall, Y up, facing +Z,
// rest pose a T-pose (arms along ±X, palms down, legs straight, feet flat and pointing +Z).
//
// Details: docs/headers/procedural.md (mocapdb/procedural/humanoid.hpp).
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
    static constexpr const char* left_toe = "LeftToeBase";          ///< foot contact joints
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
