#pragma once
// Forward kinematics: global joint positions (cm) and orientations from one frame of channels.
#include <vector>

#include "mocapdb/core/types.hpp"
#include "mocapdb/motion/clip.hpp"
#include "mocapdb/motion/skeleton.hpp"

namespace mocapdb {

/// Global pose of one frame, indexed like skeleton.joints() (end sites included).
struct GlobalPose {
    std::vector<Vec3> positions;     ///< cm, world frame
    std::vector<Quat> orientations;  ///< world-from-joint rotation
};

/// Fills out_pose for the frame row `row` (skeleton.channel_count() values). Allocation-free when
/// out_pose already has skeleton.size() entries.
void forward_kinematics(const Skeleton& skeleton, const double* row, GlobalPose& out_pose);

/// World transform of one joint.
struct JointTransform {
    Vec3 position = Vec3::Zero();         ///< cm
    Quat orientation = Quat::Identity();  ///< world-from-joint rotation
};

/// World transform of the skeleton's motion root (Skeleton::motion_root()) for one frame row: FK
/// along motion_root_chain(), so a static ROOT above a moving Hips is accounted for.
JointTransform motion_root_transform(const Skeleton& skeleton, const double* row);

/// The same from every joint's local transform (indexed like skeleton.joints(); rotations[j] and
/// translations[j] as Skeleton::local_rotation / local_translation give them for a row).
JointTransform local_root_transform(const Skeleton& skeleton, const std::vector<Quat>& rotations,
                                    const std::vector<Vec3>& translations);

/// Global pose from every joint's local transform (as above): world_j = world_parent · local_j.
/// Allocation-free when out_pose already has skeleton.size() entries.
void forward_kinematics(const Skeleton& skeleton, const std::vector<Quat>& rotations,
                        const std::vector<Vec3>& translations, GlobalPose& out_pose);

/// Global joint positions of every frame: a 3·J by F matrix (rows 3j..3j+2 hold joint j).
MatX joint_positions(const Clip& clip);

}  // namespace mocapdb
