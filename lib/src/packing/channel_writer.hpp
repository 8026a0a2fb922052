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
#include "mocapdb/packing/group_decoder.hpp"
#include "channel_lanes.hpp"

namespace mocapdb::packing::detail {

/// A clip's canonicalization with its heading rotation formed once (Canonicalization::invert forms
/// it, a sincos, on every call); invert gives Canonicalization::invert's bits (the same operations).
struct Placement {
    Placement() = default;
    explicit Placement(const Canonicalization& c)
        : heading(Eigen::AngleAxisd(c.yaw, Vec3::UnitY())), translation(c.translation) {}
    Vec3 invert(const Vec3& p) const { return heading * p + translation; }
    Quat invert(const Quat& q) const { return heading * q; }

    Quat heading = Quat::Identity();
    Vec3 translation = Vec3::Zero();
};

class ChannelWriter {
public:
    ChannelWriter() = default;
    /// Plans for `skeleton` (not kept: the writer holds copies of what it needs).
    explicit ChannelWriter(const Skeleton& skeleton);

    /// Joints whose three pose dofs are constant in the group (`varies[d]` false, value pose[d])
    /// get their channels worked out once, here, instead of per frame (the same bits).
    void fold_constants(const std::vector<bool>& varies, const double* pose);

    /// Writes the channel row (channel_count values) of `pose` (the skeleton's pose-vector dofs)
    /// placed back in the world by `placement`. Const: one writer serves any number of threads.
    void write(const double* pose, const Placement& placement, double* row) const;

    /// The same frame as local joint transforms (LocalPose, group_decoder.hpp): every joint's rotation
    /// equals, to rounding (~1e-15), Skeleton::local_rotation of the row write() gives (up to sign),
    /// its translation Skeleton::local_translation; no Euler angles are formed (exp map -> quaternion,
    /// projected onto the joint's channel axes where it has fewer than three). out must already hold
    /// size() entries in both vectors (not resized here). Non-root position channels: set_position.
    void write_local(const double* pose, const Placement& placement, LocalPose& out) const;
    /// A non-root position channel (row column `column`) with value `value` into out's translations.
    void set_position(int column, double value, LocalPose& out) const;
    /// Joints of the skeleton (LocalPose sizes).
    std::size_t size() const { return rest_rotations_.size(); }
    /// Heap bytes held (containers' capacities).
    std::size_t memory_bytes() const;

    /// A joint with rotation channels, as write_local computes it.
    struct RotationJoint {
        std::array<int, 3> cols{};  ///< channel column of each Euler axis in order, -1 when absent
        std::array<int, 3> axes{};  ///< the order's axes (0 = x, 1 = y, 2 = z)
        Vec3 weights = Vec3::Ones();
        double parity = 1.0;  ///< +1 when the order is a cyclic permutation of xyz
        int single = -1;      ///< index (0..2) in the order of the only channel, when one
        Quat axis = Quat::Identity();
        int pose_row = 0;                     ///< first of the joint's 3 values in the pose vector
        int joint = 0;                        ///< skeleton index
        int present = 0;                      ///< rotation channels (1..3; 0 for a motion root without any)
        int missing = -1;                     ///< with two channels: index (0..2) in the order of the absent axis
        Vec3 twist_axis = Vec3::UnitX();      ///< with one channel: C · its axis (local frame)
        Mat3 euler_frame = Mat3::Identity();  ///< with two channels: A (channel_lanes.hpp)
    };
    /// What write_local reads, for decoders of the same local poses outside this class (the runtime
    /// format prototype, benchmarks/): read only, valid while the writer lives.
    struct LocalView {
        const std::vector<RotationJoint>* joints;  ///< motion root first; then two, one, three channels
        std::size_t two_channel_joints, one_channel_joints;
        Quat above_inverse;
        Vec3 above_position, root_offset;
        std::array<int, 3> root_translation;
        bool root_rotates, adds;
        std::size_t motion_root;
        const std::vector<Quat>* rest_rotations;
        const std::vector<Vec3>* rest_translations;
        const std::vector<Vec3>* offsets;
    };
    LocalView local_view() const {
        return {&joints_,        two_channel_joints_, one_channel_joints_, above_inverse_,
                above_position_, root_offset_,        root_translation_,   root_rotates_,
                adds_,           motion_root_,        &rest_rotations_,    &rest_translations_,
                &offsets_};
    }

private:
    /// The Euler angles write_rotation writes (in the order's axis order; absent axes included).
    static void choose_angles(const RotationJoint& j, const Quat& local, double* angles);
    void write_rotation(const RotationJoint& j, const Quat& local, double* row) const;
    /// C · R(angles of the present channels) · C⁻¹, as Skeleton::local_rotation composes it.
    static Quat euler_rotation(const RotationJoint& j, const double* angles);
    /// The rotation of the channels write_rotation would write for `local`, without forming angles.
    static Quat channel_rotation(const RotationJoint& j, const Quat& local);
    /// Orders the joints after the motion root by their rotation channels (two, one, three) and fills
    /// the lanes of those with two and one.
    void plan_lanes();
    /// Lane l of group g of the joints joints_[first .. first + count): the group's first joint in
    /// lanes past the end (computed, dropped).
    const RotationJoint& lane_joint(std::size_t first, std::size_t count, std::size_t g, std::size_t l) const {
        const std::size_t k = 4 * g + l;
        return joints_[first + (k < count ? k : 4 * g)];
    }

    std::vector<double> rest_;  ///< channel row of the rest pose
    std::array<int, 3> root_translation_{-1, -1, -1};
    Vec3 root_offset_ = Vec3::Zero();  ///< subtracted when position channels add to the offset
    Quat above_inverse_ = Quat::Identity();
    Vec3 above_position_ = Vec3::Zero();
    bool root_rotates_ = false;
    std::vector<RotationJoint> joints_;               ///< motion root first (pose row 3), then the others
    std::size_t two_channel_joints_ = 0;              ///< joints_[1 .. 1 + this) have two rotation channels,
    std::size_t one_channel_joints_ = 0;              ///< the next this many one; the rest three
    std::vector<TwoChannelLanes> two_channel_lanes_;  ///< those joints four at a time
    std::vector<OneChannelLanes> one_channel_lanes_;
    // LocalPose: rest transforms of every joint (folded constant joints at their constant rotation),
    // the motion root's, and what a position channel column moves.
    std::vector<Quat> rest_rotations_;
    std::vector<Vec3> rest_translations_;
    std::size_t motion_root_ = 0;
    bool adds_ = true;  ///< position channels add to the offset
    std::vector<Vec3> offsets_;
    std::vector<int> column_joint_;  ///< per row column: joint of a position channel, or -1
    std::vector<int> column_axis_;
};

}  // namespace mocapdb::packing::detail
