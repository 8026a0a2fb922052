#include "mocapdb/procedural/walk.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "mocapdb/core/error.hpp"
#include "mocapdb/procedural/humanoid.hpp"
#include "rig.hpp"

namespace mocapdb::procedural {
namespace {
using namespace detail;

constexpr double kGravity = 981.0;        // cm/s²
constexpr double kWalkAnkleHeight = 8.0;  // cm, foot flat
constexpr double kStepHalfWidth = 6.5;    // cm from the path to each ankle
constexpr double kWalkToeOut = 6.0 * deg;
constexpr double kStartPhase = 0.8;   // the clip starts late in the left swing
constexpr double kAnchor = 0.3;       // the ankle passes under the pelvis path at 30 % of its cycle
constexpr double kHeelRocker = 0.08;  // heel strike → foot flat, fraction of the cycle
constexpr double kHeelRise = 0.35;    // foot flat → heel rises about the ball
constexpr double kToeOff = 0.6;       // stance ends
constexpr double kClearance = 7.0;    // cm added to the ankle's height at mid swing

double sin_over(double x) { return std::abs(x) < 1e-4 ? 1.0 - x * x / 6.0 : std::sin(x) / x; }
double one_minus_cos_over(double x) {
    return std::abs(x) < 1e-4 ? x / 2.0 - x * x * x / 24.0 : (1.0 - std::cos(x)) / x;
}

struct Gait {
    double v = 0.0;        // requested path speed, cm/s
    double vc = 0.0;       // progression speed of the centre path, cm/s
    double omega = 0.0;    // turn rate, rad/s
    double period = 0.0;   // s
    double speed_m = 0.0;  // m/s, for the style amplitudes
    double lateral = 0.0, bob = 0.0, yaw_amp = 0.0, roll_amp = 0.0, pitch = 0.0, toe_off = 0.0, heel_strike = 0.0;
    double arm_amp = 0.0;

    double phase(double t) const { return kStartPhase + t / period; }
    double heading(double t) const { return omega * t; }
    Vec3 centre(double t) const {
        const double x = omega * t;
        return Vec3(vc * t * one_minus_cos_over(x), 0.0, vc * t * sin_over(x));
    }
    static Vec3 left_of(double heading) { return Vec3(std::cos(heading), 0.0, -std::sin(heading)); }
    // Pelvis position on the floor plane (y = 0): the centre path plus sway toward the stance foot.
    Vec3 pelvis_xz(double t) const {
        return centre(t) + lateral * std::cos(2.0 * kPi * (phase(t) - 0.28)) * left_of(heading(t));
    }
    double pelvis_bob(double t) const { return bob * std::cos(4.0 * kPi * (phase(t) - 0.28)); }
    Quat pelvis_rotation(double t) const {
        const double ph = phase(t);
        const double yaw = heading(t) - yaw_amp * std::cos(2.0 * kPi * ph);
        const double roll = roll_amp * std::cos(2.0 * kPi * (ph - 0.2)) - std::atan(v * omega / kGravity);
        return rot_y(yaw) * rot_x(pitch) * rot_z(roll);
    }
};

struct FootState {
    Vec3 ankle;
    Quat foot;
    double toe = 0.0;  // toe flexion about X (local), radians
    bool planted = false;
};

class Feet {
public:
    explicit Feet(const Gait& g)
        : g_(g), ball_(Rig::get().skeleton->joint(Rig::get().toe[0]).offset), heel_(humanoid_heel_point()) {}

    FootState state(Side side, double t) const {
        const double q = g_.phase(t) - (side == kLeft ? 0.0 : 0.5);
        const double n = std::floor(q);
        const double u = q - n;
        FootState s;
        if (u < kToeOff) {
            s.planted = true;
            const Vec3 flat = footprint(side, n);
            const Quat yaw = rot_y(footprint_yaw(side, n));
            if (u < kHeelRocker) {
                const double pitch = g_.heel_strike * (1.0 - min_jerk(u / kHeelRocker));
                s.foot = yaw * rot_x(-pitch);
                s.ankle = flat + yaw * heel_ - s.foot * heel_;
            } else if (u < kHeelRise) {
                s.foot = yaw;
                s.ankle = flat;
            } else {
                const double pitch = g_.toe_off * min_jerk((u - kHeelRise) / (kToeOff - kHeelRise));
                s.foot = yaw * rot_x(pitch);
                s.ankle = flat + yaw * ball_ - s.foot * ball_;
                s.toe = -pitch;
            }
            return s;
        }
        // Swing: the foot lifts off and sets down nearly vertically (the horizontal travel starts a
        // little after toe-off and ends a little before heel strike), so that it does not skim the
        // floor slowly while near it.
        const double w = (u - kToeOff) / (1.0 - kToeOff);
        const double k = min_jerk(w);
        const double kh = min_jerk((w - 0.08) / 0.78);
        const Quat yaw0 = rot_y(footprint_yaw(side, n)), yaw1 = rot_y(footprint_yaw(side, n + 1));
        const Quat off = yaw0 * rot_x(g_.toe_off), strike = yaw1 * rot_x(-g_.heel_strike);
        const Vec3 a0 = footprint(side, n) + yaw0 * ball_ - off * ball_;
        const Vec3 a1 = footprint(side, n + 1) + yaw1 * heel_ - strike * heel_;
        const double lift = std::sin(kPi * w);
        s.ankle = (1.0 - kh) * a0 + kh * a1;
        s.ankle.y() = (1.0 - k) * a0.y() + k * a1.y() + kClearance * lift * lift;
        const double yaw = (1.0 - kh) * footprint_yaw(side, n) + kh * footprint_yaw(side, n + 1);
        s.foot = rot_y(yaw) * rot_x((1.0 - k) * g_.toe_off - k * g_.heel_strike);
        s.toe = -g_.toe_off * (1.0 - min_jerk(w / 0.4));
        return s;
    }

private:
    // Time at which footprint n of `side` is under the pelvis path.
    double anchor_time(Side side, double n) const {
        return (n + (side == kLeft ? 0.0 : 0.5) + kAnchor - kStartPhase) * g_.period;
    }
    double footprint_yaw(Side side, double n) const {
        return g_.heading(anchor_time(side, n)) + (side == kLeft ? kWalkToeOut : -kWalkToeOut);
    }
    Vec3 footprint(Side side, double n) const {
        const double t = anchor_time(side, n);
        const double sign = side == kLeft ? 1.0 : -1.0;
        return g_.centre(t) + sign * kStepHalfWidth * Gait::left_of(g_.heading(t)) + Vec3(0.0, kWalkAnkleHeight, 0.0);
    }

    const Gait& g_;
    Vec3 ball_, heel_;
};

std::string describe(const WalkParams& p) {
    std::ostringstream s;
    s << "walk (speed " << p.speed_m_s << " m/s, turn " << p.turn_deg << " deg, stride " << p.stride_m << " m)";
    return s.str();
}

}  // namespace

WalkMotion generate_walk(const WalkParams& p, const WalkOptions& o) {
    if (!std::isfinite(p.speed_m_s) || p.speed_m_s < 0.4 || p.speed_m_s > 1.9)
        throw InvalidArgument(describe(p) + ": speed must be 0.4…1.9 m/s");
    if (!std::isfinite(p.turn_deg) || std::abs(p.turn_deg) > 180.0)
        throw InvalidArgument(describe(p) + ": turn must be within ±180 degrees");
    if (!std::isfinite(p.stride_m) || (p.stride_m != 0.0 && (p.stride_m < 0.6 || p.stride_m > 2.0)))
        throw InvalidArgument(describe(p) + ": stride must be 0 (from speed) or 0.6…2.0 m");
    if (!(o.frame_rate >= 10.0 && o.frame_rate <= 1000.0)) throw InvalidArgument("walk: frame rate must be 10…1000 Hz");
    if (o.cycles < 1 || o.cycles > 20) throw InvalidArgument("walk: cycles must be 1…20");
    if (!(o.max_leg_extension >= 0.9 && o.max_leg_extension <= 0.9999))
        throw InvalidArgument("walk: max_leg_extension must be 0.9…0.9999");
    const Rig& rig = Rig::get();
    const Skeleton& sk = *rig.skeleton;

    Gait g;
    g.speed_m = p.speed_m_s;
    g.v = 100.0 * p.speed_m_s;
    const double stride_cm = p.stride_m > 0.0 ? 100.0 * p.stride_m : 80.0 + 0.4 * g.v;
    const long cycle_frames = std::max(8L, std::lround(stride_cm / g.v * o.frame_rate));
    g.period = static_cast<double>(cycle_frames) / o.frame_rate;
    const std::size_t frames = static_cast<std::size_t>(o.cycles * cycle_frames + 1);
    const double duration = static_cast<double>(frames - 1) / o.frame_rate;
    g.omega = p.turn_deg * deg / duration;
    // Style: amplitudes grow with speed.
    g.lateral = std::max(1.0, 2.8 - 0.8 * g.speed_m);
    g.yaw_amp = (3.0 + 3.0 * g.speed_m) * deg;
    g.roll_amp = 3.0 * deg;
    g.pitch = (2.0 + 2.0 * g.speed_m) * deg;
    g.toe_off = (22.0 + 8.0 * g.speed_m) * deg;
    g.heel_strike = (8.0 + 4.0 * g.speed_m) * deg;
    g.arm_amp = (8.0 + 14.0 * g.speed_m) * deg;
    std::vector<double> time(frames);
    for (std::size_t f = 0; f < frames; ++f) time[f] = static_cast<double>(f) / o.frame_rate;

    // Progression speed: the pelvis path (sway included) must be exactly v · duration long, as the
    // speed extractor measures it frame to frame.
    g.vc = g.v;
    for (int it = 0; it < 50; ++it) {
        double length = 0.0;
        for (std::size_t f = 1; f < frames; ++f) length += (g.pelvis_xz(time[f]) - g.pelvis_xz(time[f - 1])).norm();
        const double ratio = g.v * duration / length;
        g.vc *= ratio;
        if (std::abs(ratio - 1.0) < 1e-14) break;
    }

    // Pelvis height: as high as the legs allow (hip–ankle ≤ e · leg), with a bob of at least the
    // nominal amplitude peaking at mid-stance.
    const Feet feet(g);
    const double e = o.max_leg_extension, leg = rig.thigh + rig.shin;
    const double standing = -sk.joint(rig.upleg[0]).offset.y() + leg + kWalkAnkleHeight - 0.2;
    std::vector<double> ceiling(frames, standing), wave(frames);
    for (std::size_t f = 0; f < frames; ++f) {
        const double t = time[f];
        wave[f] = std::cos(4.0 * kPi * (g.phase(t) - 0.28));
        const Quat r = g.pelvis_rotation(t);
        for (const Side side : {kLeft, kRight}) {
            const Vec3 hip = g.pelvis_xz(t) + r * sk.joint(rig.upleg[side]).offset;  // root at y = 0
            const Vec3 ankle = feet.state(side, t).ankle;
            const double horizontal = std::hypot(hip.x() - ankle.x(), hip.z() - ankle.z());
            if (horizontal >= e * leg) throw InvalidArgument(describe(p) + ": the stride is too long for the legs");
            ceiling[f] =
                std::min(ceiling[f], ankle.y() - hip.y() + std::sqrt(e * e * leg * leg - horizontal * horizontal));
        }
    }
    const double nominal_bob = 1.0 + 1.0 * g.speed_m;
    double best_height = -1e300;
    for (int i = 0; i <= 60; ++i) {
        const double amp = nominal_bob * (1.0 + 1.5 * i / 60.0);
        double height = standing - amp;
        for (std::size_t f = 0; f < frames; ++f) height = std::min(height, ceiling[f] - amp * wave[f]);
        if (height > best_height + 1e-9) best_height = height, g.bob = amp;
    }
    const double base_height = best_height;

    WalkMotion m;
    m.stride_m = g.v * g.period / 100.0;
    m.cycle_s = g.period;
    m.progression_cm_s = g.vc;
    m.planted.assign(2, std::vector<bool>(frames, false));
    m.clip.skeleton = rig.skeleton;
    m.clip.frame_rate = o.frame_rate;
    m.clip.name = "walk";
    m.clip.channels =
        FrameMatrix::Zero(static_cast<Eigen::Index>(frames), static_cast<Eigen::Index>(sk.channel_count()));
    ChannelEncoder encoder(sk);
    Pose pose(sk.size());
    Globals gl;
    const double leg_limit = std::min(1.0, e + 1e-6);
    for (std::size_t f = 0; f < frames; ++f) {
        const double t = time[f], ph = g.phase(t);
        const double yaw_osc = -g.yaw_amp * std::cos(2.0 * kPi * ph);
        const double roll_osc = g.roll_amp * std::cos(2.0 * kPi * (ph - 0.2));
        pose.root = g.pelvis_xz(t) + Vec3(0.0, base_height + g.pelvis_bob(t), 0.0);
        pose.local[rig.hips] = g.pelvis_rotation(t);
        // Thorax counter-rotates the pelvis, stays upright against its list and partly against its tilt.
        for (std::size_t k = 0; k < 3; ++k)
            pose.local[rig.spine[k]] = rot_y(-0.5 * yaw_osc) * rot_x(-g.pitch / 6.0) * rot_z(-roll_osc / 3.0);
        pose.local[rig.neck] = pose.local[rig.head] = Quat::Identity();
        for (const Side k : {kLeft, kRight}) {
            // Arms swing opposite the legs; elbows bend more in the forward swing.
            const double swing = g.arm_amp * std::cos(2.0 * kPi * (ph - (k == kLeft ? 0.5 : 0.0)));
            const double sign = k == kLeft ? 1.0 : -1.0;
            pose.local[rig.clavicle[k]] = Quat::Identity();
            pose.local[rig.arm[k]] = rot_x(-swing) * rot_z(-sign * 84.0 * deg);
            const double elbow = 12.0 * deg + 0.35 * (swing + g.arm_amp);
            pose.local[rig.forearm[k]] = rot(Vec3(0.0, -sign, 0.0), elbow);
            pose.local[rig.hand[k]] = Quat::Identity();
        }
        forward(sk, pose, gl);
        // Head level, looking along the path and a little into the turn.
        const Quat wanted = rot_y(g.heading(t) + 0.4 * g.omega) * rot_x(4.0 * deg);
        const Quat q = (gl.rotation[rig.spine[2]].conjugate() * wanted).normalized();
        pose.local[rig.neck] = Quat::Identity().slerp(0.4, q);
        pose.local[rig.head] = (pose.local[rig.neck].conjugate() * q).normalized();
        forward(sk, pose, gl);
        for (const Side k : {kLeft, kRight}) {
            const FootState s = feet.state(k, t);
            solve_leg(rig, k, pose, gl, s.ankle, s.foot * Vec3::UnitZ(), &s.foot, leg_limit);
            pose.local[rig.toe[k]] = rot_x(s.toe);
            m.planted[k][f] = s.planted;
        }
        forward(sk, pose, gl);
        encoder.encode(pose, m.clip.channels.row(static_cast<Eigen::Index>(f)).data());
    }
    return m;
}

}  // namespace mocapdb::procedural
