// Clips as local rotations and root positions, and back.
#include "mocapdb/motion/local_pose_arrays.hpp"

#include <cmath>
#include <string>
#include <vector>

#include "mocapdb/core/error.hpp"
#include "mocapdb/motion/forward_kinematics.hpp"
#include "mocapdb/motion/rotation.hpp"

namespace mocapdb {
namespace {

Quat checked_quaternion(const double* q, std::size_t frame, std::size_t joint) {
    const Quat r(q[0], q[1], q[2], q[3]);
    const double n = r.norm();
    if (!std::isfinite(n) || n < 0.9 || n > 1.1)
        throw InvalidArgument("local rotations: frame " + std::to_string(frame) + ", joint " + std::to_string(joint) +
                              ": expected a unit quaternion (w, x, y, z), got norm " + std::to_string(n));
    return r.normalized();
}

Vec3 checked_position(const double* p, std::size_t frame) {
    const Vec3 v(p[0], p[1], p[2]);
    if (!v.allFinite()) throw InvalidArgument("root positions: frame " + std::to_string(frame) + ": non-finite value");
    return v;
}

}  // namespace

VecX rest_row(const Skeleton& s) {
    VecX rest = VecX::Zero(static_cast<Eigen::Index>(s.channel_count()));
    for (std::size_t j = 0; j < s.size(); ++j)
        for (int a = 0; a < 3; ++a) {
            const int col = s.channel_column(j, static_cast<ChannelType>(a));
            if (col >= 0) rest[col] = s.rest_position_value(j, static_cast<Axis>(a));
        }
    return rest;
}

void write_rotation_channels(const Skeleton& skeleton, std::size_t j, const Quat& local, const double* near_row,
                             double* row) {
    const Joint& joint = skeleton.joint(j);
    const Quat r = joint.axis.conjugate() * local * joint.axis;  // undo C · R · C⁻¹
    const auto ax = axes_of(joint.rotation_order);
    int cols[3];
    Vec3 near, weights;
    for (int k = 0; k < 3; ++k) {
        cols[k] = skeleton.channel_column(j, static_cast<ChannelType>(3 + static_cast<int>(ax[k])));
        near[k] = cols[k] >= 0 ? near_row[cols[k]] : 0.0;
        // An axis without a channel must come out at 0 (mod 2π), or dropping it would change the rotation.
        weights[k] = cols[k] >= 0 ? 1.0 : 1e6;
    }
    const Vec3 angles = matrix_to_euler_near(r.toRotationMatrix(), joint.rotation_order, near, weights);
    for (int k = 0; k < 3; ++k)
        if (cols[k] >= 0) row[cols[k]] = angles[k];
}

void local_rotations_of(const Clip& clip, double* out) {
    validate(clip);
    const Skeleton& s = *clip.skeleton;
    for (std::size_t f = 0; f < clip.frame_count(); ++f)
        for (std::size_t j = 0; j < s.size(); ++j) {
            const Quat q = s.local_rotation(j, clip.frame(f)).normalized();
            double* o = out + 4 * (f * s.size() + j);
            o[0] = q.w();
            o[1] = q.x();
            o[2] = q.y();
            o[3] = q.z();
        }
}

void root_positions_of(const Clip& clip, double* out) {
    validate(clip);
    for (std::size_t f = 0; f < clip.frame_count(); ++f) {
        const Vec3 p = clip.skeleton->local_translation(0, clip.frame(f));
        for (int a = 0; a < 3; ++a) out[3 * f + static_cast<std::size_t>(a)] = p[a];
    }
}

void forward_kinematics_of_arrays(const Skeleton& s, const double* rotations, const double* root_positions,
                                  std::size_t frames, double* out) {
    const std::size_t joints = s.size();
    std::vector<Quat> local(joints);
    std::vector<Vec3> translations(joints);
    for (std::size_t j = 0; j < joints; ++j) translations[j] = s.joint(j).offset;
    GlobalPose pose;
    for (std::size_t f = 0; f < frames; ++f) {
        for (std::size_t j = 0; j < joints; ++j) local[j] = checked_quaternion(rotations + 4 * (f * joints + j), f, j);
        translations[0] = checked_position(root_positions + 3 * f, f);
        forward_kinematics(s, local, translations, pose);
        for (std::size_t j = 0; j < joints; ++j)
            for (int a = 0; a < 3; ++a) out[3 * (f * joints + j) + static_cast<std::size_t>(a)] = pose.positions[j][a];
    }
}

FrameMatrix channels_from_local_rotations(const Skeleton& s, const double* rotations, const double* root_positions,
                                          std::size_t frames) {
    const VecX rest = rest_row(s);
    const bool adds = s.position_channels() == PositionChannels::add_to_offset;
    FrameMatrix out = rest.transpose().replicate(static_cast<Eigen::Index>(frames), 1);
    VecX near = VecX::Zero(rest.size());
    for (std::size_t f = 0; f < frames; ++f) {
        double* row = out.row(static_cast<Eigen::Index>(f)).data();
        const Vec3 p = checked_position(root_positions + 3 * f, f);
        for (int a = 0; a < 3; ++a) {
            const int col = s.channel_column(0, static_cast<ChannelType>(a));
            if (col >= 0) row[col] = p[a] - (adds ? s.joint(0).offset[a] : 0.0);
        }
        for (std::size_t j = 0; j < s.size(); ++j) {
            const Quat q = checked_quaternion(rotations + 4 * (f * s.size() + j), f, j);
            if (s.has_rotation(j)) write_rotation_channels(s, j, q, near.data(), row);
        }
        near = out.row(static_cast<Eigen::Index>(f)).transpose();
    }
    return out;
}

void quaternions_of_matrices(const double* matrices, std::size_t count, double* out) {
    for (std::size_t i = 0; i < count; ++i) {
        const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> m(matrices + 9 * i);
        const Mat3 r = m;
        if (!r.allFinite() || (r.transpose() * r - Mat3::Identity()).cwiseAbs().maxCoeff() > 1e-3 ||
            r.determinant() < 0.0)
            throw InvalidArgument("rotation matrices: matrix " + std::to_string(i) +
                                  " is not a rotation (R^T R = I, det 1)");
        const Quat q = Quat(r).normalized();
        out[4 * i] = q.w();
        out[4 * i + 1] = q.x();
        out[4 * i + 2] = q.y();
        out[4 * i + 3] = q.z();
    }
}

}  // namespace mocapdb
