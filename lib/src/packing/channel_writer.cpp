#include "channel_writer.hpp"

#include <algorithm>
#include <cmath>

#include "mocapdb/motion/rotation.hpp"

namespace mocapdb::packing::detail {

ChannelWriter::ChannelWriter(const Skeleton& s) {
    const PoseLayout layout(s);
    rest_.assign(s.channel_count(), 0.0);
    for (std::size_t j = 0; j < s.size(); ++j)
        for (int a = 0; a < 3; ++a) {
            const int col = s.channel_column(j, static_cast<ChannelType>(a));
            if (col >= 0) rest_[static_cast<std::size_t>(col)] = s.rest_position_value(j, static_cast<Axis>(a));
        }
    // Joints above the motion root stay at rest (as in from_pose_vectors).
    const std::size_t m = s.motion_root();
    Quat above = Quat::Identity();
    for (std::size_t j : s.motion_root_chain()) {
        if (j == m) break;
        above_position_ += above * s.local_translation(j, rest_.data());
        above = above * s.local_rotation(j, rest_.data());
    }
    above_inverse_ = above.conjugate();
    for (int a = 0; a < 3; ++a) root_translation_[static_cast<std::size_t>(a)] = s.channel_column(m, static_cast<ChannelType>(a));
    if (s.position_channels() == PositionChannels::add_to_offset) root_offset_ = s.joint(m).offset;
    root_rotates_ = s.has_rotation(m);
    for (std::size_t k = 0; k < layout.rotation_joints().size(); ++k) {
        const std::size_t j = layout.rotation_joints()[k];
        const Joint& joint = s.joint(j);
        RotationJoint r;
        const auto ax = axes_of(joint.rotation_order);
        int present = 0;
        for (std::size_t i = 0; i < 3; ++i) {
            r.axes[i] = static_cast<int>(ax[i]);
            r.cols[i] = s.channel_column(j, static_cast<ChannelType>(3 + static_cast<int>(ax[i])));
            // An axis without a channel must come out at 0 (mod 2π), or dropping it would change the rotation.
            r.weights[static_cast<Eigen::Index>(i)] = r.cols[i] >= 0 ? 1.0 : 1e6;
            if (r.cols[i] >= 0) {
                ++present;
                r.single = static_cast<int>(i);
            }
        }
        if (present != 1) r.single = -1;
        r.parity = (r.axes[1] - r.axes[0] + 3) % 3 == 1 ? 1.0 : -1.0;
        r.axis = joint.axis;
        r.pose_row = layout.exp_map_row(j);
        joints_.push_back(r);
    }
}

namespace {
constexpr double kTwoPi = 2.0 * kPi;
// Into [-π, π] (inputs within 2π of it).
double wrap(double a) { return a > kPi ? a - kTwoPi : a < -kPi ? a + kTwoPi : a; }
}  // namespace

void ChannelWriter::write_rotation(const RotationJoint& j, const Quat& local, double* row) const {
    const Quat r = j.axis.conjugate() * local * j.axis;  // undo C · R · C⁻¹
    if (j.single >= 0) {
        // One channel: the twist about its axis (what is left off the axis has no channel anyway).
        const auto i = static_cast<std::size_t>(j.single);
        row[j.cols[i]] = wrap(2.0 * std::atan2(r.vec()[j.axes[i]], r.w()));
        return;
    }
    // R = R_i(a) R_j(b) R_k(c): R(i,k) = s·sin b, R(i,i) = cos b cos c, R(i,j) = -s cos b sin c,
    // R(k,k) = cos a cos b, R(j,k) = -s sin a cos b (as matrix_to_euler), and of the two families
    // (a, b, c) and (a + π, π − b, c + π) the one nearest zero, absent axes weighted 1e6.
    const Mat3 m = r.toRotationMatrix();
    const int i = j.axes[0], k = j.axes[2], jj = j.axes[1];
    const double s = j.parity;
    const double cos_b = std::sqrt(m(i, i) * m(i, i) + m(i, jj) * m(i, jj));
    const double b = std::atan2(s * m(i, k), cos_b);
    double a, c;
    if (cos_b > 1e-12) {
        a = std::atan2(-s * m(jj, k), m(k, k));
        c = std::atan2(-s * m(i, jj), m(i, i));
    } else {
        a = std::atan2(s * m(k, jj), m(jj, jj));  // gimbal lock: all of a ± c in a
        c = 0.0;
    }
    const double first[3] = {a, b, c};
    const double second[3] = {wrap(a + kPi), wrap(kPi - b), wrap(c + kPi)};
    double d1 = 0.0, d2 = 0.0;
    for (int n = 0; n < 3; ++n) {
        d1 += j.weights[n] * first[n] * first[n];
        d2 += j.weights[n] * second[n] * second[n];
    }
    const double* angles = d1 <= d2 ? first : second;
    for (std::size_t n = 0; n < 3; ++n)
        if (j.cols[n] >= 0) row[j.cols[n]] = angles[n];
}

void ChannelWriter::fold_constants(const std::vector<bool>& varies, const double* pose) {
    std::vector<RotationJoint> kept{joints_.front()};  // the root depends on the clip's canonicalization
    for (std::size_t k = 1; k < joints_.size(); ++k) {
        const auto d = static_cast<std::size_t>(joints_[k].pose_row);
        if (varies[d] || varies[d + 1] || varies[d + 2]) {
            kept.push_back(joints_[k]);
            continue;
        }
        const double* v = pose + d;
        write_rotation(joints_[k], exp_map(Vec3(v[0], v[1], v[2])), rest_.data());
    }
    joints_ = std::move(kept);
}

void ChannelWriter::write(const double* pose, const Canonicalization& canonical, double* row) const {
    std::copy(rest_.begin(), rest_.end(), row);
    const Vec3 local = above_inverse_ * (canonical.invert(Vec3(pose[0], pose[1], pose[2])) - above_position_);
    for (std::size_t a = 0; a < 3; ++a)
        if (root_translation_[a] >= 0)
            row[root_translation_[a]] = local[static_cast<Eigen::Index>(a)] - root_offset_[static_cast<Eigen::Index>(a)];
    const Quat root_rotation = above_inverse_ * canonical.invert(swing_twist_exp(Vec3(pose[3], pose[4], pose[5])));
    if (root_rotates_) write_rotation(joints_.front(), root_rotation, row);
    for (std::size_t k = 1; k < joints_.size(); ++k) {
        const double* v = pose + joints_[k].pose_row;
        write_rotation(joints_[k], exp_map(Vec3(v[0], v[1], v[2])), row);
    }
}

}  // namespace mocapdb::packing::detail
