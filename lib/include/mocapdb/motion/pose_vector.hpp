#pragma once
// The pose-vector representation the later math works in, and its exact inverse.
//
// Details: docs/headers/motion.md (mocapdb/motion/pose_vector.hpp).
#include <vector>

#include "mocapdb/core/types.hpp"
#include "mocapdb/motion/clip.hpp"
#include "mocapdb/motion/forward_kinematics.hpp"

namespace mocapdb {

/// p_canonical = R_y(−yaw) · (p − translation); q_canonical = R_y(−yaw) · q.
struct Canonicalization {
    Vec3 translation = Vec3::Zero();  ///< (x, 0, z) of the first frame's root, cm
    double yaw = 0.0;                 ///< heading of the first frame about +Y, radians

    Vec3 apply(const Vec3& world_position) const;
    Quat apply(const Quat& world_orientation) const;
    Vec3 invert(const Vec3& canonical_position) const;
    Quat invert(const Quat& canonical_orientation) const;
};

/// Which joints the pose vector holds, and where.
class PoseLayout {
public:
    explicit PoseLayout(const Skeleton& skeleton);
    /// D, the length of one pose vector.
    std::size_t dof_count() const noexcept { return 6 + 3 * (rotation_joints_.size() - 1); }
    /// Skeleton indices of the joints with rows: the motion root first, then the joints with rotation
    /// channels outside its chain, in skeleton order.
    const std::vector<std::size_t>& rotation_joints() const noexcept { return rotation_joints_; }
    /// First row of joint `skeleton_index`'s exp map, or −1 when the joint has no rotation.
    int exp_map_row(std::size_t skeleton_index) const;

private:
    std::vector<std::size_t> rotation_joints_;
    std::vector<int> rows_;
};

/// Heading (yaw about +Y) of a world orientation for a skeleton facing `forward` at rest.
double heading_of(const Quat& orientation, const Vec3& forward);

/// The canonicalization defined by the clip's first frame.
Canonicalization canonicalization_of(const Clip& clip);
/// The same from the first frame's motion-root world transform and the skeleton's forward direction.
Canonicalization canonicalization_of(const JointTransform& first_root, const Vec3& forward);

/// Pose vectors of every frame: D by F. `reference` (D values, may be empty) is the vector the first
/// frame's exp maps are chosen nearest to; empty means the principal branch.
MatX to_pose_vectors(const Clip& clip, const Canonicalization& canonical, const VecX& reference = VecX());

/// One frame's pose vector (D values into out) from its joints' local transforms (indexed like
/// skeleton.joints(), as forward kinematics composes them: Skeleton::local_rotation and
/// local_translation of a frame row), exp-map branches nearest `near` (D values): the column
/// to_pose_vectors gives for that row. For decoders that hold rotations rather than Euler channels
/// (packing::LocalPose). InvalidArgument on wrong sizes.
void pose_vector_from_local(const Skeleton& skeleton, const PoseLayout& layout, const std::vector<Quat>& rotations,
                            const std::vector<Vec3>& translations, const Canonicalization& canonical,
                            const Eigen::Ref<const VecX>& near, Eigen::Ref<VecX> out);
/// Channel rows from pose vectors (D by F): the exact inverse of to_pose_vectors for rotations the
/// joint's channels can express (others are projected: missing axes are dropped). Euler angles are
/// unwrapped against the previous frame; the first frame against `first_near` (a frame row, may be
/// empty = zeros). Returns F by skeleton.channel_count().
FrameMatrix from_pose_vectors(const Skeleton& skeleton, const Eigen::Ref<const MatX>& poses,
                              const Canonicalization& canonical, const VecX& first_near = VecX());

}  // namespace mocapdb
