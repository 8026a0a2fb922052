#include "mocapdb/procedural/reach.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>

#include "mocapdb/core/error.hpp"
#include "mocapdb/motion/forward_kinematics.hpp"
#include "mocapdb/procedural/humanoid.hpp"
#include "mocapdb/procedural/two_bone_ik.hpp"
#include "rig.hpp"

namespace mocapdb::procedural {
namespace {
using namespace detail;

constexpr double kStandDrop = 0.2;        // cm below straight legs when standing
constexpr double kLegExtension = 0.9995;  // standing legs may be almost straight
constexpr double kArmExtension = 0.995;
constexpr double kMaxPelvisYaw = 0.35;     // share of the body turn taken by the pelvis (the spine takes the rest)
constexpr double kMaxLean = 40.0 * deg;    // hip flexion at full lean
constexpr double kSpineLean = 12.0 * deg;  // per spine joint at full lean
constexpr double kCrouch = 24.0;           // cm the pelvis sinks at full lean
constexpr double kHipsBack = 14.0;         // cm the pelvis moves back at full lean (balance)
constexpr double kToeOut = 6.0 * deg;
constexpr double kAnkleHeight = 8.0;  // cm, feet flat

std::string describe(const ReachParams& p) {
    std::ostringstream s;
    s << "reach target (angle " << p.angle_deg << " deg, height " << p.height_cm << " cm, distance " << p.distance_cm
      << " cm)";
    return s.str();
}

// Where the feet stand: ankles under the hips, toes slightly out.
struct Stance {
    Vec3 ankle[2];
    Quat foot[2];
};

Stance standing_stance(const Rig& rig) {
    const Skeleton& s = *rig.skeleton;
    Stance st;
    for (int k = 0; k < 2; ++k) {
        const double hip_x = s.joint(rig.upleg[k]).offset.x();
        st.ankle[k] = Vec3(hip_x, kAnkleHeight, 0.0);
        st.foot[k] = rot_y(k == kLeft ? kToeOut : -kToeOut);
    }
    return st;
}

double standing_height(const Rig& rig) {
    const Skeleton& s = *rig.skeleton;
    return -s.joint(rig.upleg[0]).offset.y() + rig.thigh + rig.shin + kAnkleHeight - kStandDrop;
}

// The whole-body pose at one instant of the reach (everything but the right arm when `hang_right` is
// false). yaw: body turn (rad), lean 0…1, clavicle 0…1 (right shoulder girdle toward the target),
// look: head weight toward `look_at`.
struct BodyPose {
    double yaw = 0.0, lean = 0.0, clavicle = 0.0, look = 0.0, elevation = 0.0;
};

void pose_body(const Rig& rig, const Stance& stance, const BodyPose& b, const Vec3& look_at, bool hang_right,
               Pose& pose, Globals& g) {
    const Skeleton& s = *rig.skeleton;
    const double pelvis_yaw = kMaxPelvisYaw * b.yaw;
    const Quat heading = rot_y(pelvis_yaw);
    pose.root = Vec3(0.0, standing_height(rig) - kCrouch * b.lean * b.lean, 0.0) +
                heading * Vec3(0.0, 0.0, -kHipsBack * b.lean);
    pose.local[rig.hips] = heading * rot_x(kMaxLean * b.lean);
    for (std::size_t k = 0; k < 3; ++k)
        pose.local[rig.spine[k]] = rot_y((1.0 - kMaxPelvisYaw) * b.yaw / 3.0) * rot_x(kSpineLean * b.lean);
    // Right shoulder girdle: forward (protraction) and up for high targets.
    pose.local[rig.clavicle[kRight]] = rot_y(10.0 * deg * b.clavicle) * rot_z(-b.elevation * b.clavicle);
    pose.local[rig.clavicle[kLeft]] = Quat::Identity();
    pose.local[rig.neck] = pose.local[rig.head] = Quat::Identity();
    forward(s, pose, g);
    // Head looks at the target (split between neck and head, limited).
    if (b.look > 0.0) {
        const Quat chest = g.rotation[rig.spine[2]];
        const Vec3 d = chest.conjugate() * (look_at - g.position[rig.head]);
        const double yaw = std::clamp(std::atan2(d.x(), d.z()), -75.0 * deg, 75.0 * deg);
        const double pitch = std::clamp(std::atan2(-d.y(), std::hypot(d.x(), d.z())), -40.0 * deg, 60.0 * deg);
        pose.local[rig.neck] = rot_y(0.4 * b.look * yaw) * rot_x(0.4 * b.look * pitch);
        pose.local[rig.head] = rot_y(0.6 * b.look * yaw) * rot_x(0.6 * b.look * pitch);
        forward(s, pose, g);
    }
    // Legs: feet planted, knees over the toes.
    for (const Side k : {kLeft, kRight}) {
        const Vec3 knee_pole = rot_y(0.5 * pelvis_yaw) * stance.foot[k] * Vec3::UnitZ();
        solve_leg(rig, k, pose, g, stance.ankle[k], knee_pole, &stance.foot[k], kLegExtension);
    }
    // Arms hang under gravity, elbows back, hands slightly forward and out.
    const Quat chest_heading = rot_y(b.yaw);
    for (const Side k : {kLeft, kRight}) {
        if (k == kRight && !hang_right) continue;
        const double out = k == kLeft ? 4.0 : -4.0;
        const Vec3 target = g.position[rig.arm[k]] + Vec3(0.0, -0.96 * (rig.upper_arm + rig.lower_arm), 0.0) +
                            chest_heading * Vec3(out, 0.0, 4.0);
        solve_arm(rig, k, pose, g, target, chest_heading * Vec3(0.0, 0.0, -1.0), nullptr, 1.0);
    }
}

Quat hand_rotation_toward(const Vec3& direction, const Quat& chest) {
    // Right hand: bone along −X, palm normal −Y in the T-pose. Reaching, the palm faces in and down.
    Vec3 palm = chest * Vec3(0.7, -0.7, 0.0);
    if ((palm - palm.dot(direction) * direction).norm() < 1e-6) palm = chest * Vec3(0.0, 0.0, 1.0);
    return frame_rotation(Vec3(-1, 0, 0), Vec3(0, -1, 0), direction, palm);
}

}  // namespace

Vec3 reach_target(const ReachParams& p) {
    if (!std::isfinite(p.angle_deg) || std::abs(p.angle_deg) > 150.0)
        throw InvalidArgument(describe(p) + ": angle must be within ±150 degrees");
    if (!std::isfinite(p.height_cm) || p.height_cm < 30.0 || p.height_cm > 200.0)
        throw InvalidArgument(describe(p) + ": height must be 30…200 cm");
    if (!std::isfinite(p.distance_cm) || p.distance_cm < 20.0 || p.distance_cm > 95.0)
        throw InvalidArgument(describe(p) + ": distance must be 20…95 cm");
    if (!std::isfinite(p.elbow_swivel_deg) || std::abs(p.elbow_swivel_deg) > 90.0)
        throw InvalidArgument(describe(p) + ": elbow swivel must be within ±90 degrees");
    const double a = p.angle_deg * deg;
    return Vec3(p.distance_cm * std::sin(a), p.height_cm, p.distance_cm * std::cos(a));
}

ReachMotion generate_reach(const ReachParams& params, const ReachOptions& o) {
    const Vec3 target = reach_target(params);
    if (!(o.frame_rate >= 10.0 && o.frame_rate <= 1000.0))
        throw InvalidArgument("reach: frame rate must be 10…1000 Hz");
    if (!(o.lead_in_s >= 0.0 && o.hold_s >= 0.0 && o.lead_out_s >= 0.0 && o.target_width_cm > 0.0 &&
          o.return_ratio > 0.1 && o.lead_in_s <= 10.0 && o.hold_s <= 10.0 && o.lead_out_s <= 10.0 &&
          o.return_ratio <= 10.0))
        throw InvalidArgument("reach: durations must be 0…10 s, target width positive, return ratio 0.1…10");
    const Rig& rig = Rig::get();
    const Skeleton& s = *rig.skeleton;
    const Stance stance = standing_stance(rig);

    // The body's final posture: turn toward the target, lean and crouch just enough to reach it.
    ReachMotion m;
    m.target = target;
    const double bearing = params.angle_deg * deg;
    BodyPose final_body;
    final_body.yaw = std::clamp(0.8 * bearing, -70.0 * deg, 75.0 * deg);
    final_body.clavicle = 1.0;
    final_body.look = 1.0;
    final_body.elevation = std::clamp((params.height_cm - 130.0) / 60.0, -0.3, 1.0) * 15.0 * deg;
    const double hand = s.joint(rig.hand_end[kRight]).offset.norm();
    const double arm = rig.upper_arm + rig.lower_arm;
    const double soft = hand + 0.95 * arm, hard = hand + kArmExtension * arm, nearest = hand + 0.3 * arm;
    Pose pose(s.size());
    Globals g;
    double best_lean = -1.0, best_excess = 1e300;
    for (int i = 0; i <= 100; ++i) {
        final_body.lean = i / 100.0;
        pose_body(rig, stance, final_body, target, true, pose, g);
        const double d = (target - g.position[rig.arm[kRight]]).norm();
        const double excess = std::max(0.0, d - soft) + std::max(0.0, nearest - d);
        if (excess == 0.0) {
            best_lean = final_body.lean;
            best_excess = 0.0;
            break;
        }
        if (excess < best_excess) best_excess = excess, best_lean = final_body.lean;
    }
    final_body.lean = best_lean;
    pose_body(rig, stance, final_body, target, true, pose, g);
    const Vec3 shoulder = g.position[rig.arm[kRight]];
    const double reach_distance = (target - shoulder).norm();
    if (reach_distance > hard)
        throw InvalidArgument(describe(params) + " is out of reach: " + std::to_string(reach_distance - hard) +
                              " cm beyond the arm with the body turned and bent as far as it goes");
    if (reach_distance < nearest)
        throw InvalidArgument(describe(params) + " is too close to the right shoulder to reach");
    m.body_turn = final_body.yaw;
    m.lean = final_body.lean;

    // Final hand orientation and elbow pole (down, out and back in the chest's frame, then swivelled).
    const Quat chest_final = g.rotation[rig.spine[2]];
    const Vec3 reach_dir = (target - shoulder).normalized();
    const Quat hand_final = hand_rotation_toward(reach_dir, chest_final);
    Vec3 pole_reach = chest_final * Vec3(-0.5, -1.0, -0.3);
    pole_reach = rot(reach_dir, -params.elbow_swivel_deg * deg) * pole_reach;
    const Vec3 hand_offset = s.joint(rig.hand_end[kRight]).offset;

    // Rest posture (hanging arms): where the hand starts.
    BodyPose rest;
    pose_body(rig, stance, rest, target, true, pose, g);
    const Vec3 hand_start = g.position[rig.hand_end[kRight]];
    const Quat hand_rest = g.rotation[rig.hand[kRight]];
    const Vec3 chest_start = g.position[rig.spine[2]];

    // Timing: Fitts' law on the hand's travel plus the body's turn.
    const double travel = (target - hand_start).norm();
    m.reach_seconds = 0.25 + 0.1 * std::log2(1.0 + travel / o.target_width_cm) + 0.25 * std::abs(final_body.yaw);
    const auto frames_of = [&](double seconds, long minimum) {
        return static_cast<std::size_t>(std::max(minimum, std::lround(seconds * o.frame_rate)));
    };
    const std::size_t n_in = frames_of(o.lead_in_s, 0), n_reach = frames_of(m.reach_seconds, 2);
    const std::size_t n_hold = frames_of(o.hold_s, 0), n_back = frames_of(o.return_ratio * m.reach_seconds, 2);
    const std::size_t n_out = frames_of(o.lead_out_s, 0);
    m.reach_begin = n_in;
    m.contact_frame = n_in + n_reach;
    m.release_frame = m.contact_frame + n_hold;
    const std::size_t frames = m.release_frame + n_back + n_out + 1;

    // The hand's path bows outward, away from the chest, by up to 12 cm at its middle.
    const Vec3 middle = 0.5 * (hand_start + target);
    Vec3 bow = middle - chest_start;
    bow.y() = 0.0;
    bow = bow.norm() > 1e-6 ? Vec3(12.0 * bow.normalized()) : Vec3::Zero();

    m.clip.skeleton = rig.skeleton;
    m.clip.frame_rate = o.frame_rate;
    m.clip.name = "reach";
    m.clip.channels =
        FrameMatrix::Zero(static_cast<Eigen::Index>(frames), static_cast<Eigen::Index>(s.channel_count()));
    ChannelEncoder encoder(s);
    for (std::size_t f = 0; f < frames; ++f) {
        // Progress s along the reach (0 rest, 1 on the target) and the head's lead.
        double progress = 0.0, look = 0.0;
        if (f >= m.reach_begin && f <= m.contact_frame) {
            const double tau = static_cast<double>(f - m.reach_begin) / static_cast<double>(n_reach);
            progress = f == m.contact_frame ? 1.0 : min_jerk(tau);
            look = min_jerk(1.5 * tau);
        } else if (f > m.contact_frame && f <= m.release_frame) {
            progress = look = 1.0;
        } else if (f > m.release_frame && f < m.release_frame + n_back) {
            const double tau = static_cast<double>(f - m.release_frame) / static_cast<double>(n_back);
            progress = 1.0 - min_jerk(tau);
            look = 1.0 - min_jerk(1.3 * tau);
        }
        BodyPose body = final_body;
        body.yaw *= progress;
        body.lean *= progress;
        body.clavicle = progress;
        body.look = look;
        pose_body(rig, stance, body, target, progress == 0.0, pose, g);
        if (progress > 0.0) {
            const bool on_target = progress == 1.0;
            const Vec3 hand_pos =
                on_target ? target
                          : Vec3(hand_start + progress * (target - hand_start) + std::sin(kPi * progress) * bow);
            const Quat hand_rot = on_target ? hand_final : hand_rest.slerp(progress, hand_final);
            const Vec3 pole_hang = rot_y(body.yaw) * Vec3(0.0, 0.0, -1.0);
            const Vec3 pole = (1.0 - progress) * pole_hang + progress * pole_reach;
            Vec3 wrist = hand_pos - hand_rot * hand_offset;
            if (!on_target) {
                // Soft reach: on the way, a wrist goal near or beyond full extension is pulled in
                // smoothly (the elbow would otherwise snap straight and bend again fast); the pull
                // fades in after rest and out toward contact, where the goal is met exactly.
                const Vec3 sh = g.position[rig.arm[kRight]];
                const double c = (wrist - sh).norm(), start = 0.85 * arm, range = kArmExtension * arm - start;
                if (c > start) {
                    const double pulled = start + range * (1.0 - std::exp(-(c - start) / range));
                    const double weight = std::sin(kPi * progress);  // 0 at rest and at contact
                    wrist = sh + (wrist - sh) * ((c - weight * (c - pulled)) / c);
                }
            }
            const bool reached =
                solve_arm(rig, kRight, pose, g, wrist, pole, &hand_rot, on_target ? kArmExtension : 1.0);
            if (on_target && !reached)
                throw InvalidArgument(describe(params) + " is out of reach of the arm");  // excluded above
        }
        encoder.encode(pose, m.clip.channels.row(static_cast<Eigen::Index>(f)).data());
    }
    return m;
}

std::optional<Vec3> reach_hold_point(const Clip& clip) {
    const auto hand = clip.skeleton ? clip.skeleton->find(HumanoidNames::right_hand_end) : std::nullopt;
    if (!hand || clip.frame_count() < 3) return std::nullopt;
    const MatX p = joint_positions(clip);
    const Eigen::Index row = 3 * static_cast<Eigen::Index>(*hand);
    const Vec3 start = p.block<3, 1>(row, 0);
    double farthest = 0.0;
    for (Eigen::Index f = 0; f < p.cols(); ++f) farthest = std::max(farthest, (p.block<3, 1>(row, f) - start).norm());
    Eigen::Index hold = 0;
    double slowest = std::numeric_limits<double>::infinity();
    for (Eigen::Index f = 1; f + 1 < p.cols(); ++f) {
        if ((p.block<3, 1>(row, f) - start).norm() < 0.8 * farthest) continue;
        const double speed = (p.block<3, 1>(row, f + 1) - p.block<3, 1>(row, f - 1)).norm();
        if (speed < slowest) {
            slowest = speed;
            hold = f;
        }
    }
    return Vec3(p.block<3, 1>(row, hold));
}

}  // namespace mocapdb::procedural
