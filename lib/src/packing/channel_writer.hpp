#pragma once
// One pose vector -> one channel row, the packed group's per-frame decode step (internal to the
// packing module). What from_pose_vectors does for a clip, for a single frame and with everything
// that depends only on the skeleton worked out once: rest values, the transform above the motion
// root, channel columns, bone axes and rotation orders.
//
// Euler angles are chosen nearest zero for every frame (not nearest the previous frame), so a frame
// decodes on its own and gives the same bits whether decoded alone or with its window; the
// forward-kinematics pose is the same either way, only the 2π branch of a channel may differ. A joint
// with one rotation channel takes its twist about that axis (one atan2 instead of three); the
// encoder verifies the bound on exactly these values.
#include <array>
#include <cstddef>
#include <vector>

#include "mocapdb/core/types.hpp"
#include "mocapdb/motion/pose_vector.hpp"
#include "mocapdb/motion/skeleton.hpp"

namespace mocapdb::packing::detail {

class ChannelWriter {
public:
    ChannelWriter() = default;
    /// Plans for `skeleton` (not kept: the writer holds copies of what it needs).
    explicit ChannelWriter(const Skeleton& skeleton);

    /// Joints whose three pose dofs are constant in the group (`varies[d]` false, value pose[d])
    /// get their channels worked out once, here, instead of per frame (the same bits).
    void fold_constants(const std::vector<bool>& varies, const double* pose);

    /// Writes the channel row (channel_count values) of `pose` (the skeleton's pose-vector dofs)
    /// placed back in the world by `canonical`. Const: one writer serves any number of threads.
    void write(const double* pose, const Canonicalization& canonical, double* row) const;

private:
    struct RotationJoint {
        std::array<int, 3> cols{};  ///< channel column of each Euler axis in order, -1 when absent
        std::array<int, 3> axes{};  ///< the order's axes (0 = x, 1 = y, 2 = z)
        Vec3 weights = Vec3::Ones();
        double parity = 1.0;        ///< +1 when the order is a cyclic permutation of xyz
        int single = -1;            ///< index (0..2) in the order of the only channel, when one
        Quat axis = Quat::Identity();
        int pose_row = 0;           ///< first of the joint's 3 values in the pose vector
    };
    void write_rotation(const RotationJoint& j, const Quat& local, double* row) const;

    std::vector<double> rest_;             ///< channel row of the rest pose
    std::array<int, 3> root_translation_{-1, -1, -1};
    Vec3 root_offset_ = Vec3::Zero();      ///< subtracted when position channels add to the offset
    Quat above_inverse_ = Quat::Identity();
    Vec3 above_position_ = Vec3::Zero();
    bool root_rotates_ = false;
    std::vector<RotationJoint> joints_;    ///< motion root first (pose row 3), then the others
};

}  // namespace mocapdb::packing::detail
