#pragma once
// Analytic two-bone inverse kinematics (shoulder-elbow-wrist, hip-knee-ankle).
#include "mocapdb/core/types.hpp"

namespace mocapdb::procedural {

struct TwoBoneSolution {
    Vec3 middle;           ///< elbow / knee position, world cm
    Vec3 end;              ///< wrist / ankle position actually reached, world cm
    Vec3 hinge;            ///< unit axis the middle joint bends about (world)
    double bend = 0.0;     ///< angle between the two bones' directions, radians (0 = straight)
    bool reached = false;  ///< false when the target was out of [|l1 − l2|, max_extension · (l1 + l2)]
};

/// Places the middle joint of a chain root → middle → end with bone lengths `upper` and `lower` (cm,
/// positive) so that the end lies on `target`, bending toward `pole` (a direction, world; only its
/// component perpendicular to root → target matters). A target beyond max_extension · (upper + lower)
/// or nearer than |upper − lower| is replaced by the nearest reachable point on the line root → target
/// (reached = false). `max_extension` in (0, 1] keeps the chain from locking straight, where the bend
/// angle changes fastest. InvalidArgument for non-positive lengths or a target on the root.
TwoBoneSolution solve_two_bone(const Vec3& root, double upper, double lower, const Vec3& target, const Vec3& pole,
                               double max_extension = 1.0);

/// The rotation that takes the rest frame (rest_direction, rest_hinge) onto (direction, hinge). Both
/// pairs must be orthonormal (the rest pair is orthonormalized first). Used to turn an IK solution into
/// a bone's global orientation with the bend axis where the joint's rest hinge is.
Quat frame_rotation(const Vec3& rest_direction, const Vec3& rest_hinge, const Vec3& direction, const Vec3& hinge);

}  // namespace mocapdb::procedural
