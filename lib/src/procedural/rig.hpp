#pragma once
// Private to the procedural generators: posing the humanoid with local rotations, forward kinematics
// on such poses, limb IK on the humanoid, and encoding poses into channel rows with continuous Euler
// angles.
#include <array>
#include <memory>
#include <vector>

#include "mocapdb/core/types.hpp"
#include "mocapdb/motion/skeleton.hpp"

namespace mocapdb::procedural::detail {

enum Side { kLeft = 0, kRight = 1 };

/// Joint indices of the humanoid, resolved by name once.
struct Rig {
    std::shared_ptr<const Skeleton> skeleton;
    std::size_t hips, spine[3], neck, head;
    std::array<std::size_t, 2> clavicle, arm, forearm, hand, hand_end;
    std::array<std::size_t, 2> upleg, leg, foot, toe;
    double upper_arm, lower_arm, thigh, shin;  ///< bone lengths, cm

    static const Rig& get();
};

/// A pose: the root joint's world position (cm) and a local rotation per joint (end sites: identity).
struct Pose {
    Vec3 root = Vec3::Zero();
    std::vector<Quat> local;
    explicit Pose(std::size_t joints) : local(joints, Quat::Identity()) {}
};

struct Globals {
    std::vector<Vec3> position;
    std::vector<Quat> rotation;
};

void forward(const Skeleton& skeleton, const Pose& pose, Globals& out);

/// Rotation by `angle` about the unit axis.
inline Quat rot(const Vec3& axis, double angle) { return Quat(Eigen::AngleAxisd(angle, axis)); }
inline Quat rot_x(double a) { return rot(Vec3::UnitX(), a); }
inline Quat rot_y(double a) { return rot(Vec3::UnitY(), a); }
inline Quat rot_z(double a) { return rot(Vec3::UnitZ(), a); }
constexpr double deg = 3.14159265358979323846 / 180.0;

/// Minimum-jerk profile 10τ³ − 15τ⁴ + 6τ⁵ of τ clamped to [0, 1].
double min_jerk(double tau);

/// Solves a limb (arm or leg of `side`) so that its end joint (wrist / ankle) is at `target`, bending
/// toward `pole`, then sets the end joint's local rotation so that its global rotation is
/// `*end_rotation` (null: the end joint keeps the identity local rotation). `globals` must hold the pose's FK (the limb's parents are read from it); it is
/// recomputed on return. Returns whether the target was reached.
bool solve_arm(const Rig& rig, Side side, Pose& pose, Globals& globals, const Vec3& target, const Vec3& pole,
               const Quat* end_rotation, double max_extension);
bool solve_leg(const Rig& rig, Side side, Pose& pose, Globals& globals, const Vec3& target, const Vec3& pole,
               const Quat* end_rotation, double max_extension);

/// Writes poses into channel rows, choosing each joint's Euler angles nearest the previous row's.
class ChannelEncoder {
public:
    explicit ChannelEncoder(const Skeleton& skeleton);
    void encode(const Pose& pose, double* out_row);

private:
    const Skeleton& skeleton_;
    std::vector<Vec3> previous_;
};

}  // namespace mocapdb::procedural::detail
