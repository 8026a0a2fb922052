#include "rig.hpp"

#include <algorithm>
#include <string>

#include "mocapdb/core/error.hpp"
#include "mocapdb/motion/rotation.hpp"
#include "mocapdb/procedural/humanoid.hpp"
#include "mocapdb/procedural/two_bone_ik.hpp"

namespace mocapdb::procedural::detail {
namespace {

std::size_t index_of(const Skeleton& s, const std::string& name) {
    const auto j = s.find(name);
    if (!j) throw InvalidArgument("humanoid skeleton: no joint '" + name + "'");  // a bug in humanoid.cpp
    return *j;
}

// Sets the local rotations of upper, middle and end so that the chain reaches `target`.
bool solve_limb(const Skeleton& s, std::size_t upper, std::size_t middle, std::size_t end, const Vec3& rest_hinge,
                Pose& pose, Globals& g, const Vec3& target, const Vec3& pole, const Quat* end_rotation,
                double max_extension) {
    const Vec3 d0 = s.joint(middle).offset.normalized();
    const double l1 = s.joint(middle).offset.norm();
    const double l2 = s.joint(end).offset.norm();
    const Vec3 root = g.position[upper];
    const TwoBoneSolution ik = solve_two_bone(root, l1, l2, target, pole, max_extension);
    const Quat upper_global = frame_rotation(d0, rest_hinge, (ik.middle - root) / l1, ik.hinge);
    const Quat& parent = g.rotation[static_cast<std::size_t>(s.joint(upper).parent)];
    pose.local[upper] = (parent.conjugate() * upper_global).normalized();
    pose.local[middle] = rot(rest_hinge, ik.bend);
    const Quat middle_global = upper_global * pose.local[middle];
    pose.local[end] = end_rotation ? (middle_global.conjugate() * *end_rotation).normalized() : Quat::Identity();
    forward(s, pose, g);
    return ik.reached;
}

}  // namespace

const Rig& Rig::get() {
    static const Rig rig = [] {
        Rig r;
        r.skeleton = humanoid_skeleton();
        const Skeleton& s = *r.skeleton;
        r.hips = index_of(s, "Hips");
        r.spine[0] = index_of(s, "Spine");
        r.spine[1] = index_of(s, "Spine1");
        r.spine[2] = index_of(s, "Spine2");
        r.neck = index_of(s, "Neck");
        r.head = index_of(s, "Head");
        const char* sides[2] = {"Left", "Right"};
        for (int k = 0; k < 2; ++k) {
            const std::string side = sides[k];
            r.clavicle[k] = index_of(s, side + "Shoulder");
            r.arm[k] = index_of(s, side + "Arm");
            r.forearm[k] = index_of(s, side + "ForeArm");
            r.hand[k] = index_of(s, side + "Hand");
            r.hand_end[k] = index_of(s, side + "Hand_end");
            r.upleg[k] = index_of(s, side + "UpLeg");
            r.leg[k] = index_of(s, side + "Leg");
            r.foot[k] = index_of(s, side + "Foot");
            r.toe[k] = index_of(s, side + "ToeBase");
        }
        r.upper_arm = s.joint(r.forearm[0]).offset.norm();
        r.lower_arm = s.joint(r.hand[0]).offset.norm();
        r.thigh = s.joint(r.leg[0]).offset.norm();
        r.shin = s.joint(r.foot[0]).offset.norm();
        return r;
    }();
    return rig;
}

void forward(const Skeleton& s, const Pose& pose, Globals& out) {
    out.position.resize(s.size());
    out.rotation.resize(s.size());
    out.position[0] = pose.root;
    out.rotation[0] = pose.local[0];
    for (std::size_t j = 1; j < s.size(); ++j) {
        const auto p = static_cast<std::size_t>(s.joint(j).parent);
        out.position[j] = out.position[p] + out.rotation[p] * s.joint(j).offset;
        out.rotation[j] = (out.rotation[p] * pose.local[j]).normalized();
    }
}

double min_jerk(double tau) {
    const double t = std::clamp(tau, 0.0, 1.0);
    return t * t * t * (10.0 + t * (-15.0 + 6.0 * t));
}

bool solve_arm(const Rig& rig, Side side, Pose& pose, Globals& globals, const Vec3& target, const Vec3& pole,
               const Quat* end_rotation, double max_extension) {
    // Rest hinge: elbow flexion swings the forearm forward (+Z) from the T-pose.
    const Vec3 hinge = side == kRight ? Vec3::UnitY() : Vec3(-Vec3::UnitY());
    return solve_limb(*rig.skeleton, rig.arm[side], rig.forearm[side], rig.hand[side], hinge, pose, globals, target,
                      pole, end_rotation, max_extension);
}

bool solve_leg(const Rig& rig, Side side, Pose& pose, Globals& globals, const Vec3& target, const Vec3& pole,
               const Quat* end_rotation, double max_extension) {
    // Rest hinge: knee flexion swings the shin backward (−Z).
    return solve_limb(*rig.skeleton, rig.upleg[side], rig.leg[side], rig.foot[side], Vec3::UnitX(), pose, globals,
                      target, pole, end_rotation, max_extension);
}

ChannelEncoder::ChannelEncoder(const Skeleton& skeleton)
    : skeleton_(skeleton), previous_(skeleton.size(), Vec3::Zero()) {}

void ChannelEncoder::encode(const Pose& pose, double* row) {
    const Skeleton& s = skeleton_;
    for (std::size_t j = 0; j < s.size(); ++j) {
        const Joint& joint = s.joint(j);
        if (joint.end_site) continue;
        for (int a = 0; a < 3; ++a) {
            const int col = s.channel_column(j, static_cast<ChannelType>(a));
            // Only the root has position channels; they hold its translation (or the part beyond its offset).
            if (col >= 0) row[col] = pose.root[a] - (joint.offset[a] - s.rest_position_value(j, static_cast<Axis>(a)));
        }
        if (!s.has_rotation(j)) continue;
        const Vec3 angles = matrix_to_euler_near(pose.local[j].toRotationMatrix(), joint.rotation_order, previous_[j]);
        const auto axes = axes_of(joint.rotation_order);
        for (int k = 0; k < 3; ++k)
            row[s.channel_column(
                j, static_cast<ChannelType>(3 + static_cast<int>(axes[static_cast<std::size_t>(k)])))] = angles[k];
        previous_[j] = angles;
    }
}

}  // namespace mocapdb::procedural::detail
