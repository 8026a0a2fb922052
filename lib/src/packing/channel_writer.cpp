#include "channel_writer.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "exp_map_batch.hpp"
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
    for (int a = 0; a < 3; ++a)
        root_translation_[static_cast<std::size_t>(a)] = s.channel_column(m, static_cast<ChannelType>(a));
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
        r.joint = static_cast<int>(j);
        r.present = present;
        for (int i = 0; i < 3; ++i)
            if (present == 2 && r.cols[static_cast<std::size_t>(i)] < 0) r.missing = i;
        if (r.single >= 0) r.twist_axis = joint.axis * Vec3::Unit(r.axes[static_cast<std::size_t>(r.single)]);
        if (present == 2) r.euler_frame = detail::euler_frame(r.axes.data(), r.parity, r.axis);
        joints_.push_back(r);
    }
    plan_lanes();
    motion_root_ = m;
    adds_ = s.position_channels() == PositionChannels::add_to_offset;
    column_joint_.assign(s.channel_count(), -1);
    column_axis_.assign(s.channel_count(), 0);
    for (std::size_t j = 0; j < s.size(); ++j) {
        rest_rotations_.push_back(s.local_rotation(j, rest_.data()));
        rest_translations_.push_back(s.local_translation(j, rest_.data()));
        offsets_.push_back(s.joint(j).offset);
        for (int a = 0; a < 3; ++a) {
            const int col = s.channel_column(j, static_cast<ChannelType>(a));
            if (col < 0) continue;
            column_joint_[static_cast<std::size_t>(col)] = static_cast<int>(j);
            column_axis_[static_cast<std::size_t>(col)] = a;
        }
    }
}

namespace {
constexpr double kTwoPi = 2.0 * kPi;
// Into [-π, π] (inputs within 2π of it).
double wrap(double a) { return a > kPi ? a - kTwoPi : a < -kPi ? a + kTwoPi : a; }
}  // namespace

void ChannelWriter::write_rotation(const RotationJoint& j, const Quat& local, double* row) const {
    double angles[3];
    choose_angles(j, local, angles);
    for (std::size_t n = 0; n < 3; ++n)
        if (j.cols[n] >= 0) row[j.cols[n]] = angles[n];
}

void ChannelWriter::choose_angles(const RotationJoint& j, const Quat& local, double* out) {
    const Quat r = j.axis.conjugate() * local * j.axis;  // undo C · R · C⁻¹
    if (j.single >= 0) {
        // One channel: the twist about its axis (what is left off the axis has no channel anyway).
        const auto i = static_cast<std::size_t>(j.single);
        out[0] = out[1] = out[2] = 0.0;
        out[i] = wrap(2.0 * std::atan2(r.vec()[j.axes[i]], r.w()));
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
    std::copy(angles, angles + 3, out);
}

Quat ChannelWriter::euler_rotation(const RotationJoint& j, const double* angles) {
    Quat r = Quat::Identity();
    for (std::size_t n = 0; n < 3; ++n)
        if (j.cols[n] >= 0) r = r * Eigen::AngleAxisd(angles[n], Vec3::Unit(j.axes[n]));
    if (j.axis.w() != 1.0) r = j.axis * r * j.axis.conjugate();
    return r;
}

namespace {
// (cos θ/2, sin θ/2) of θ = atan2(y, x), without the atan2: the half-angle direction is (h + x, y)
// (h = |(x, y)|), or equivalently (|y|, sign(y)·(h − x)) where x < 0 (no cancellation either way).
void half_angle(double x, double y, double& c, double& s) {
    const double h = std::sqrt(x * x + y * y);
    if (h == 0.0) {
        c = 1.0;
        s = 0.0;
        return;
    }
    const double a = x >= 0.0 ? h + x : h - x;
    const double n = std::sqrt(a * a + y * y);
    if (x >= 0.0) {
        c = a / n;
        s = y / n;
    } else {
        c = std::abs(y) / n;
        s = std::copysign(a, y) / n;
    }
}
}  // namespace

Quat ChannelWriter::channel_rotation(const RotationJoint& j, const Quat& local) {
    if (j.present == 3) return local;  // three Euler angles express any rotation: no projection
    if (j.single >= 0) {
        // The twist about C·axis: (w, (v·u) u), normalized (what choose_angles' one atan2 encodes).
        const double w = local.w();
        const double s = local.vec().dot(j.twist_axis);
        const double n = std::sqrt(w * w + s * s);
        if (n == 0.0) return Quat::Identity();
        const Vec3 v = (s / n) * j.twist_axis;
        return Quat(w / n, v.x(), v.y(), v.z());
    }
    double angles[3];
    if (j.present == 2) {
        // Two channels: the rotation of the two kept angles of the Euler family choose_angles picks,
        // from their half-angle cosines and sines. Its family test (weighted angles nearest zero,
        // the absent axis weighted 1e6) reduces to the sign of the absent angle's cosine unless that
        // cosine is within 1e-5 of 0 (there, and in gimbal lock, the angles are formed as written).
        const Quat r = j.axis.conjugate() * local * j.axis;
        const Mat3 m = r.toRotationMatrix();
        const int i = j.axes[0], k = j.axes[2], jj = j.axes[1];
        const double s = j.parity;
        const double cos_b = std::sqrt(m(i, i) * m(i, i) + m(i, jj) * m(i, jj));
        if (cos_b > 1e-5) {
            const double x[3] = {m(k, k), cos_b, m(i, i)};
            const double y[3] = {-s * m(jj, k), s * m(i, k), -s * m(i, jj)};
            const auto miss = static_cast<std::size_t>(j.missing);
            const double h = std::sqrt(x[miss] * x[miss] + y[miss] * y[miss]);
            const double cosine = h > 0.0 ? x[miss] / h : 1.0;
            if (std::abs(cosine) > 1e-5) {
                const bool second = cosine < 0.0;  // the family (a + π, π − b, c + π)
                Quat q = Quat::Identity();
                for (std::size_t n = 0; n < 3; ++n) {
                    if (n == miss) continue;
                    double c, sn;
                    half_angle(x[n], y[n], c, sn);
                    if (second) {
                        const double c0 = c;
                        if (n == 1) {  // (π − b)/2
                            c = sn;
                            sn = c0;
                        } else {  // (θ + π)/2
                            c = -sn;
                            sn = c0;
                        }
                    }
                    // The factor's components by selects, not by a store into one lane of it (a
                    // scalar store then read as a vector stalls store forwarding).
                    const int a = j.axes[n];
                    const Quat f(c, a == 0 ? sn : 0.0, a == 1 ? sn : 0.0, a == 2 ? sn : 0.0);
                    q = q * f;
                }
                return j.axis * q * j.axis.conjugate();
            }
        }
    }
    choose_angles(j, local, angles);
    return euler_rotation(j, angles);
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
        double angles[3] = {0.0, 0.0, 0.0};
        for (std::size_t n = 0; n < 3; ++n)
            if (joints_[k].cols[n] >= 0) angles[n] = rest_[static_cast<std::size_t>(joints_[k].cols[n])];
        rest_rotations_[static_cast<std::size_t>(joints_[k].joint)] = euler_rotation(joints_[k], angles);
    }
    joints_ = std::move(kept);
    plan_lanes();
}

void ChannelWriter::plan_lanes() {
    if (joints_.empty()) return;
    const auto two = std::stable_partition(joints_.begin() + 1, joints_.end(),
                                           [](const RotationJoint& j) { return j.present == 2; });
    const auto one = std::stable_partition(two, joints_.end(), [](const RotationJoint& j) { return j.present == 1; });
    two_channel_joints_ = static_cast<std::size_t>(two - joints_.begin()) - 1;
    one_channel_joints_ = static_cast<std::size_t>(one - two);
    two_channel_lanes_.assign((two_channel_joints_ + 3) / 4, TwoChannelLanes{});
    for (std::size_t k = 0; k < two_channel_joints_; ++k) {
        const RotationJoint& j = joints_[1 + k];
        set_lane(two_channel_lanes_[k / 4], static_cast<int>(k % 4), j.euler_frame, j.missing);
    }
    one_channel_lanes_.assign((one_channel_joints_ + 3) / 4, OneChannelLanes{});
    for (std::size_t k = 0; k < one_channel_joints_; ++k)
        for (int a = 0; a < 3; ++a)
            one_channel_lanes_[k / 4].axis[a][k % 4] = joints_[1 + two_channel_joints_ + k].twist_axis[a];
}

void ChannelWriter::write(const double* pose, const Placement& placement, double* row) const {
    std::copy(rest_.begin(), rest_.end(), row);
    const Vec3 local = above_inverse_ * (placement.invert(Vec3(pose[0], pose[1], pose[2])) - above_position_);
    for (std::size_t a = 0; a < 3; ++a)
        if (root_translation_[a] >= 0)
            row[root_translation_[a]] =
                local[static_cast<Eigen::Index>(a)] - root_offset_[static_cast<Eigen::Index>(a)];
    const Quat root_rotation = above_inverse_ * placement.invert(swing_twist_exp(Vec3(pose[3], pose[4], pose[5])));
    if (root_rotates_) write_rotation(joints_.front(), root_rotation, row);
    for (std::size_t k = 1; k < joints_.size(); ++k) {
        const double* v = pose + joints_[k].pose_row;
        write_rotation(joints_[k], exp_map(Vec3(v[0], v[1], v[2])), row);
    }
}

void ChannelWriter::write_local(const double* pose, const Placement& placement, LocalPose& out) const {
    // Whole arrays at once (std::copy moved the Vec3s a double at a time).
    std::memcpy(static_cast<void*>(out.rotations.data()), rest_rotations_.data(),
                rest_rotations_.size() * sizeof(Quat));
    std::memcpy(static_cast<void*>(out.translations.data()), rest_translations_.data(),
                rest_translations_.size() * sizeof(Vec3));
    // The motion root: as write() forms its channels, then as Skeleton::local_translation reads them.
    const Vec3 local = above_inverse_ * (placement.invert(Vec3(pose[0], pose[1], pose[2])) - above_position_);
    Vec3& t = out.translations[motion_root_];
    for (std::size_t a = 0; a < 3; ++a)
        if (root_translation_[a] >= 0) {
            const auto e = static_cast<Eigen::Index>(a);
            const double value = local[e] - root_offset_[e];
            t[e] = adds_ ? offsets_[motion_root_][e] + value : value;
        }
    if (root_rotates_) {
        // swing_twist_exp with both exp maps in lanes (libm's sincos was 5 % of a local pose).
        Lane4 w, x, y, z;
        exp_maps(Lane4{pose[3], 0.0, 0.0, 0.0}, Lane4{0.0, pose[4], 0.0, 0.0}, Lane4{pose[5], 0.0, 0.0, 0.0}, w, x, y,
                 z);
        const Quat swing(w[0], x[0], y[0], z[0]), twist(w[1], x[1], y[1], z[1]);
        const Quat root_rotation = above_inverse_ * placement.invert((swing * twist).normalized());
        out.rotations[motion_root_] = channel_rotation(joints_.front(), root_rotation);
    }
    // The other joints four at a time (lanes of one kind of joint), each one's exp map, then its
    // projection onto its channels. Joints with two channels take their exp maps in their Euler frames.
    const auto put = [&out](const RotationJoint& j, const Lane4& w, const Lane4& x, const Lane4& y, const Lane4& z,
                            std::size_t l) {
        out.rotations[static_cast<std::size_t>(j.joint)] = Quat(w[l], x[l], y[l], z[l]);
    };
    std::size_t first = 1;
    for (std::size_t g = 0; g < two_channel_lanes_.size(); ++g) {
        Vec3 a[4];
        for (std::size_t l = 0; l < 4; ++l) {
            const RotationJoint& j = lane_joint(first, two_channel_joints_, g, l);
            const double* v = pose + j.pose_row;
            a[l] = j.euler_frame * Vec3(v[0], v[1], v[2]);
        }
        Lane4 w, x, y, z, ow, ox, oy, oz;
        exp_maps(Lane4{a[0].x(), a[1].x(), a[2].x(), a[3].x()}, Lane4{a[0].y(), a[1].y(), a[2].y(), a[3].y()},
                 Lane4{a[0].z(), a[1].z(), a[2].z(), a[3].z()}, w, x, y, z);
        const unsigned left = project_two_channels(two_channel_lanes_[g], w, x, y, z, ow, ox, oy, oz);
        for (std::size_t l = 0; l < 4 && 4 * g + l < two_channel_joints_; ++l) {
            const RotationJoint& j = joints_[first + 4 * g + l];
            if ((left >> l & 1u) != 0) {  // near gimbal lock or the family boundary: as channel_rotation
                const double* v = pose + j.pose_row;
                out.rotations[static_cast<std::size_t>(j.joint)] = channel_rotation(j, exp_map(Vec3(v[0], v[1], v[2])));
            } else {
                put(j, ow, ox, oy, oz, l);
            }
        }
    }
    first += two_channel_joints_;
    // Exp maps of the joints [first, first + count) in lane group g.
    const auto exp_lanes = [&](std::size_t count, std::size_t g, Lane4& w, Lane4& x, Lane4& y, Lane4& z) {
        const double* v[4];
        for (std::size_t l = 0; l < 4; ++l) v[l] = pose + lane_joint(first, count, g, l).pose_row;
        exp_maps(Lane4{v[0][0], v[1][0], v[2][0], v[3][0]}, Lane4{v[0][1], v[1][1], v[2][1], v[3][1]},
                 Lane4{v[0][2], v[1][2], v[2][2], v[3][2]}, w, x, y, z);
    };
    for (std::size_t g = 0; g < one_channel_lanes_.size(); ++g) {
        Lane4 w, x, y, z, ow, ox, oy, oz;
        exp_lanes(one_channel_joints_, g, w, x, y, z);
        project_one_channel(one_channel_lanes_[g], w, x, y, z, ow, ox, oy, oz);
        for (std::size_t l = 0; l < 4 && 4 * g + l < one_channel_joints_; ++l)
            put(joints_[first + 4 * g + l], ow, ox, oy, oz, l);
    }
    first += one_channel_joints_;
    const std::size_t three = joints_.size() - first;  // three channels: any rotation, no projection
    for (std::size_t g = 0; 4 * g < three; ++g) {
        Lane4 w, x, y, z;
        exp_lanes(three, g, w, x, y, z);
        for (std::size_t l = 0; l < 4 && 4 * g + l < three; ++l) put(joints_[first + 4 * g + l], w, x, y, z, l);
    }
}

void ChannelWriter::set_position(int column, double value, LocalPose& out) const {
    const int joint = column_joint_[static_cast<std::size_t>(column)];
    if (joint < 0) return;
    const auto j = static_cast<std::size_t>(joint);
    const int a = column_axis_[static_cast<std::size_t>(column)];
    out.translations[j][a] = adds_ ? offsets_[j][a] + value : value;
}

std::size_t ChannelWriter::memory_bytes() const {
    return rest_.capacity() * sizeof(double) + joints_.capacity() * sizeof(RotationJoint) +
           two_channel_lanes_.capacity() * sizeof(TwoChannelLanes) +
           one_channel_lanes_.capacity() * sizeof(OneChannelLanes) + rest_rotations_.capacity() * sizeof(Quat) +
           rest_translations_.capacity() * sizeof(Vec3) + offsets_.capacity() * sizeof(Vec3) +
           (column_joint_.capacity() + column_axis_.capacity()) * sizeof(int);
}

}  // namespace mocapdb::packing::detail
