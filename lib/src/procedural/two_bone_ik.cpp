#include "mocapdb/procedural/two_bone_ik.hpp"

#include <algorithm>
#include <cmath>

#include "mocapdb/core/error.hpp"

namespace mocapdb::procedural {
namespace {

// A unit vector perpendicular to unit `n`, as close as possible to `hint`.
Vec3 perpendicular(const Vec3& n, const Vec3& hint) {
    Vec3 m = hint - hint.dot(n) * n;
    if (m.norm() > 1e-9 * std::max(1.0, hint.norm())) return m.normalized();
    // The hint is parallel to n: any perpendicular, chosen deterministically.
    const Vec3 axis = std::abs(n.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
    return (axis - axis.dot(n) * n).normalized();
}

}  // namespace

TwoBoneSolution solve_two_bone(const Vec3& root, double upper, double lower, const Vec3& target, const Vec3& pole,
                               double max_extension) {
    if (!(upper > 0.0) || !(lower > 0.0) || !std::isfinite(upper) || !std::isfinite(lower))
        throw InvalidArgument("two-bone IK: bone lengths must be positive and finite");
    if (!(max_extension > 0.0 && max_extension <= 1.0))
        throw InvalidArgument("two-bone IK: max_extension must be in (0, 1]");
    if (!root.allFinite() || !target.allFinite() || !pole.allFinite())
        throw InvalidArgument("two-bone IK: root, target and pole must be finite");
    const Vec3 d = target - root;
    const double distance = d.norm();
    if (distance < 1e-9) throw InvalidArgument("two-bone IK: the target is on the root joint");
    const Vec3 n = d / distance;
    const double longest = max_extension * (upper + lower);
    const double shortest = std::abs(upper - lower) + 1e-9 * (upper + lower);
    const double c = std::clamp(distance, shortest, longest);
    TwoBoneSolution s;
    s.reached = c == distance;
    const Vec3 m = perpendicular(n, pole);
    const double cos_a = std::clamp((upper * upper + c * c - lower * lower) / (2.0 * upper * c), -1.0, 1.0);
    const double sin_a = std::sqrt(std::max(0.0, 1.0 - cos_a * cos_a));
    s.middle = root + upper * (cos_a * n + sin_a * m);
    s.end = root + c * n;
    s.hinge = m.cross(n).normalized();
    const Vec3 u = (s.middle - root) / upper;
    const Vec3 f = (s.end - s.middle) / lower;
    s.bend = std::atan2(u.cross(f).dot(s.hinge), u.dot(f));
    return s;
}

Quat frame_rotation(const Vec3& rest_direction, const Vec3& rest_hinge, const Vec3& direction, const Vec3& hinge) {
    const Vec3 a = rest_direction.normalized();
    const Vec3 b = (rest_hinge - rest_hinge.dot(a) * a).normalized();
    const Vec3 c = direction.normalized();
    const Vec3 e = (hinge - hinge.dot(c) * c).normalized();
    Mat3 rest, now;
    rest << a, b, a.cross(b);
    now << c, e, c.cross(e);
    return Quat(Mat3(now * rest.transpose())).normalized();
}

}  // namespace mocapdb::procedural
