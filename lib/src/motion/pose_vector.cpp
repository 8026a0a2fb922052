#include "mocapdb/motion/pose_vector.hpp"

#include <cmath>

#include "mocapdb/core/error.hpp"
#include "mocapdb/motion/forward_kinematics.hpp"
#include "mocapdb/motion/local_pose_arrays.hpp"
#include "mocapdb/motion/pose_vector_positions.hpp"
#include "mocapdb/motion/rotation.hpp"

namespace mocapdb {
namespace {

Quat yaw_rotation(double yaw) { return Quat(Eigen::AngleAxisd(yaw, Vec3::UnitY())); }

// World transform of the motion root's parent at rest.
JointTransform above_motion_root(const Skeleton& s, const VecX& rest) {
    JointTransform above;
    for (std::size_t j : s.motion_root_chain()) {
        if (j == s.motion_root()) break;
        above.position += above.orientation * s.local_translation(j, rest.data());
        above.orientation = above.orientation * s.local_rotation(j, rest.data());
    }
    return above;
}

void check_pose_vectors(const Skeleton& s, const PoseLayout& layout, const Eigen::Ref<const MatX>& poses,
                        const char* where) {
    if (poses.rows() != static_cast<Eigen::Index>(layout.dof_count()))
        throw InvalidArgument(std::string(where) + ": poses have " + std::to_string(poses.rows()) +
                              " rows, the skeleton's pose vector has " + std::to_string(layout.dof_count()));
    if (!poses.allFinite()) throw InvalidArgument(std::string(where) + ": non-finite pose value");
    (void)s;
}

bool has_all_rotation_channels(const Skeleton& s, std::size_t j) {
    for (int a = 3; a < 6; ++a)
        if (s.channel_column(j, static_cast<ChannelType>(a)) < 0) return false;
    return true;
}

}  // namespace

Vec3 Canonicalization::apply(const Vec3& p) const { return yaw_rotation(-yaw) * (p - translation); }
Quat Canonicalization::apply(const Quat& q) const { return yaw_rotation(-yaw) * q; }
Vec3 Canonicalization::invert(const Vec3& p) const { return yaw_rotation(yaw) * p + translation; }
Quat Canonicalization::invert(const Quat& q) const { return yaw_rotation(yaw) * q; }

PoseLayout::PoseLayout(const Skeleton& skeleton) : rows_(skeleton.size(), -1) {
    const auto& chain = skeleton.motion_root_chain();
    rows_[skeleton.motion_root()] = 3;
    rotation_joints_.push_back(skeleton.motion_root());
    for (std::size_t j = chain.back() + 1; j < skeleton.size(); ++j) {
        if (skeleton.has_rotation(j)) {
            rows_[j] = static_cast<int>(3 + 3 * rotation_joints_.size());
            rotation_joints_.push_back(j);
        }
    }
}

int PoseLayout::exp_map_row(std::size_t skeleton_index) const { return rows_.at(skeleton_index); }

double heading_of(const Quat& orientation, const Vec3& forward) {
    const Vec3 f = orientation * forward;
    // Rotation about +Y by θ takes +Z to (sin θ, 0, cos θ); measure the heading relative to the
    // skeleton's own rest forward direction.
    const double rest = std::atan2(forward.x(), forward.z());
    if (std::hypot(f.x(), f.z()) < 1e-9) return 0.0;  // facing straight up or down: heading undefined
    return std::atan2(f.x(), f.z()) - rest;
}

Canonicalization canonicalization_of(const JointTransform& first_root, const Vec3& forward) {
    Canonicalization c;
    c.translation = Vec3(first_root.position.x(), 0.0, first_root.position.z());
    c.yaw = heading_of(first_root.orientation, forward);
    return c;
}

Canonicalization canonicalization_of(const Clip& clip) {
    validate(clip);
    if (clip.frame_count() == 0) return Canonicalization{};
    const Skeleton& s = *clip.skeleton;
    return canonicalization_of(motion_root_transform(s, clip.frame(0)), s.forward());
}

namespace {

/// One frame's pose vector: the root's canonical position and heading-relative orientation, then each
/// rotating joint's exp map, branches nearest `near`. local_rotation(j) gives joint j's local rotation.
template <class LocalRotation>
void pose_vector_of_frame(const PoseLayout& layout, const JointTransform& root, const LocalRotation& local_rotation,
                          const Canonicalization& canonical, const Eigen::Ref<const VecX>& near, Eigen::Ref<VecX> out) {
    out.head<3>() = canonical.apply(root.position);
    out.segment<3>(3) = swing_twist_log(canonical.apply(root.orientation), near.segment<3>(3));
    for (std::size_t k = 1; k < layout.rotation_joints().size(); ++k) {
        const std::size_t j = layout.rotation_joints()[k];
        const Eigen::Index r = layout.exp_map_row(j);
        out.segment<3>(r) = log_map_near(local_rotation(j), near.segment<3>(r));
    }
}

}  // namespace

void pose_vector_from_local(const Skeleton& skeleton, const PoseLayout& layout, const std::vector<Quat>& rotations,
                            const std::vector<Vec3>& translations, const Canonicalization& canonical,
                            const Eigen::Ref<const VecX>& near, Eigen::Ref<VecX> out) {
    const auto dofs = static_cast<Eigen::Index>(layout.dof_count());
    if (rotations.size() != skeleton.size() || translations.size() != skeleton.size() || near.size() != dofs ||
        out.size() != dofs)
        throw InvalidArgument("pose_vector_from_local: expected " + std::to_string(skeleton.size()) +
                              " local transforms and pose vectors of " + std::to_string(dofs) + " values");
    pose_vector_of_frame(
        layout, local_root_transform(skeleton, rotations, translations), [&](std::size_t j) { return rotations[j]; },
        canonical, near, out);
}

MatX to_pose_vectors(const Clip& clip, const Canonicalization& canonical, const VecX& reference) {
    validate(clip);
    const Skeleton& s = *clip.skeleton;
    const PoseLayout layout(s);
    const auto dofs = static_cast<Eigen::Index>(layout.dof_count());
    if (reference.size() != 0 && reference.size() != dofs)
        throw InvalidArgument("to_pose_vectors: reference has " + std::to_string(reference.size()) +
                              " values, the pose vector has " + std::to_string(dofs));
    const auto frames = static_cast<Eigen::Index>(clip.frame_count());
    MatX out(dofs, frames);
    VecX near = reference.size() ? reference : VecX::Zero(dofs);
    for (Eigen::Index f = 0; f < frames; ++f) {
        const double* row = clip.frame(static_cast<std::size_t>(f));
        pose_vector_of_frame(
            layout, motion_root_transform(s, row), [&](std::size_t j) { return s.local_rotation(j, row); }, canonical,
            near, out.col(f));
        near = out.col(f);
    }
    return out;
}

FrameMatrix from_pose_vectors(const Skeleton& s, const Eigen::Ref<const MatX>& poses, const Canonicalization& canonical,
                              const VecX& first_near) {
    const PoseLayout layout(s);
    const auto channels = static_cast<Eigen::Index>(s.channel_count());
    if (poses.rows() != static_cast<Eigen::Index>(layout.dof_count()))
        throw InvalidArgument("from_pose_vectors: poses have " + std::to_string(poses.rows()) +
                              " rows, the skeleton's pose vector has " + std::to_string(layout.dof_count()));
    if (first_near.size() != 0 && first_near.size() != channels)
        throw InvalidArgument("from_pose_vectors: first_near has " + std::to_string(first_near.size()) +
                              " values, a frame row has " + std::to_string(channels));
    if (!poses.allFinite()) throw InvalidArgument("from_pose_vectors: non-finite pose value");
    const VecX rest = rest_row(s);
    const std::size_t m = s.motion_root();
    const JointTransform above = above_motion_root(s, rest);
    const Quat above_inverse = above.orientation.conjugate();
    const bool adds = s.position_channels() == PositionChannels::add_to_offset;
    FrameMatrix out = rest.transpose().replicate(poses.cols(), 1);
    VecX near = first_near.size() ? first_near : VecX::Zero(channels);
    for (Eigen::Index f = 0; f < poses.cols(); ++f) {
        double* row = out.row(f).data();
        const Vec3 local = above_inverse * (canonical.invert(Vec3(poses.col(f).head<3>())) - above.position);
        for (int a = 0; a < 3; ++a) {
            const int col = s.channel_column(m, static_cast<ChannelType>(a));
            if (col >= 0) row[col] = local[a] - (adds ? s.joint(m).offset[a] : 0.0);
        }
        const Quat root_rotation = above_inverse * canonical.invert(swing_twist_exp(poses.col(f).segment<3>(3)));
        if (s.has_rotation(m)) write_rotation_channels(s, m, root_rotation, near.data(), row);
        for (std::size_t k = 1; k < layout.rotation_joints().size(); ++k) {
            const std::size_t j = layout.rotation_joints()[k];
            write_rotation_channels(s, j, exp_map(poses.col(f).segment<3>(layout.exp_map_row(j))), near.data(), row);
        }
        near = out.row(f).transpose();
    }
    return out;
}

MatX pose_vector_joint_positions(const Skeleton& s, const Eigen::Ref<const MatX>& poses,
                                 const Canonicalization& canonical) {
    const PoseLayout layout(s);
    check_pose_vectors(s, layout, poses, "pose_vector_joint_positions");
    const VecX rest = rest_row(s);
    const std::size_t m = s.motion_root();
    const JointTransform above = above_motion_root(s, rest);
    const Quat above_inverse = above.orientation.conjugate();
    const bool adds = s.position_channels() == PositionChannels::add_to_offset;
    const std::size_t joints = s.size();
    // Local rotations: the rest row's for joints the pose vector does not rotate.
    std::vector<Quat> rest_rotations(joints), rotations(joints);
    for (std::size_t j = 0; j < joints; ++j) rest_rotations[j] = s.local_rotation(j, rest.data());
    std::vector<Vec3> translations(joints);
    std::vector<char> direct(joints, 0);
    for (std::size_t j = 0; j < joints; ++j) direct[j] = has_all_rotation_channels(s, j) ? 1 : 0;
    VecX row = rest, near = VecX::Zero(rest.size());
    MatX out(3 * static_cast<Eigen::Index>(joints), poses.cols());
    GlobalPose pose;
    for (Eigen::Index f = 0; f < poses.cols(); ++f) {
        // The channel row from_pose_vectors writes, for the joints that still go through channels.
        const Vec3 local = above_inverse * (canonical.invert(Vec3(poses.col(f).head<3>())) - above.position);
        for (int a = 0; a < 3; ++a) {
            const int col = s.channel_column(m, static_cast<ChannelType>(a));
            if (col >= 0) row[col] = local[a] - (adds ? s.joint(m).offset[a] : 0.0);
        }
        rotations = rest_rotations;
        const Quat root_rotation = above_inverse * canonical.invert(swing_twist_exp(poses.col(f).segment<3>(3)));
        if (s.has_rotation(m)) {
            if (direct[m]) rotations[m] = root_rotation;
            else write_rotation_channels(s, m, root_rotation, near.data(), row.data());
        }
        for (std::size_t k = 1; k < layout.rotation_joints().size(); ++k) {
            const std::size_t j = layout.rotation_joints()[k];
            const Quat q = exp_map(poses.col(f).segment<3>(layout.exp_map_row(j)));
            if (direct[j]) rotations[j] = q;
            else write_rotation_channels(s, j, q, near.data(), row.data());
        }
        for (std::size_t j = 0; j < joints; ++j) {
            translations[j] = s.local_translation(j, row.data());
            if (!direct[j] && layout.exp_map_row(j) >= 0) rotations[j] = s.local_rotation(j, row.data());
        }
        forward_kinematics(s, rotations, translations, pose);
        for (std::size_t j = 0; j < joints; ++j)
            out.block<3, 1>(3 * static_cast<Eigen::Index>(j), f) = pose.positions[j];
        near = row;
    }
    return out;
}

}  // namespace mocapdb
