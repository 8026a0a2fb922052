#pragma once
// World joint positions straight from pose vectors (the compress rank search runs forward
// kinematics on 600 000 poses per probe). The same poses as forward_kinematics of
// from_pose_vectors' channel rows, without the Euler round trip where it changes nothing: a joint
// with all three rotation channels takes its exp map's rotation directly (C R(euler(C^-1 q C)) C^-1
// = q up to rounding), a joint with fewer channels still goes through its channels (the dropped
// axes project the rotation, unwrapped against the previous frame as from_pose_vectors does).
#include "mocapdb/core/types.hpp"
#include "mocapdb/motion/pose_vector.hpp"
#include "mocapdb/motion/skeleton.hpp"

namespace mocapdb {

/// Joint positions (3 J by F, joint j in rows 3j..3j+2, skeleton order) of pose vectors (D by F),
/// the first frame's Euler angles unwrapped against zeros. Equal to forward_kinematics of
/// from_pose_vectors(skeleton, poses, canonical) up to rounding (last bits). InvalidArgument on a
/// pose vector of the wrong length or a non-finite value. Pure; safe to call from several threads.
MatX pose_vector_joint_positions(const Skeleton& skeleton, const Eigen::Ref<const MatX>& poses,
                                 const Canonicalization& canonical);

}  // namespace mocapdb
