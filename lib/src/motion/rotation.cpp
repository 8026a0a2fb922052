#include "mocapdb/motion/rotation.hpp"

#include <cctype>
#include <cmath>

namespace mocapdb {
namespace {

constexpr double kTwoPi = 2.0 * kPi;

int index(Axis a) { return static_cast<int>(a); }

// +1 when (i, j, k) is a cyclic permutation of (X, Y, Z), -1 otherwise.
double parity(const std::array<Axis, 3>& ax) { return ((index(ax[1]) - index(ax[0]) + 3) % 3 == 1) ? 1.0 : -1.0; }

double wrap_near(double angle, double near) { return angle - kTwoPi * std::round((angle - near) / kTwoPi); }

}  // namespace

std::array<Axis, 3> axes_of(EulerOrder order) {
    switch (order) {
        case EulerOrder::XYZ: return {Axis::X, Axis::Y, Axis::Z};
        case EulerOrder::XZY: return {Axis::X, Axis::Z, Axis::Y};
        case EulerOrder::YXZ: return {Axis::Y, Axis::X, Axis::Z};
        case EulerOrder::YZX: return {Axis::Y, Axis::Z, Axis::X};
        case EulerOrder::ZXY: return {Axis::Z, Axis::X, Axis::Y};
        case EulerOrder::ZYX: return {Axis::Z, Axis::Y, Axis::X};
    }
    return {Axis::X, Axis::Y, Axis::Z};
}

std::optional<EulerOrder> euler_order_from_axes(Axis a, Axis b, Axis c) {
    for (EulerOrder o :
         {EulerOrder::XYZ, EulerOrder::XZY, EulerOrder::YXZ, EulerOrder::YZX, EulerOrder::ZXY, EulerOrder::ZYX}) {
        const auto ax = axes_of(o);
        if (ax[0] == a && ax[1] == b && ax[2] == c) return o;
    }
    return std::nullopt;
}

std::optional<EulerOrder> euler_order_from_string(std::string_view text) {
    if (text.size() != 3) return std::nullopt;
    Axis ax[3];
    for (int i = 0; i < 3; ++i) {
        switch (std::toupper(static_cast<unsigned char>(text[i]))) {
            case 'X': ax[i] = Axis::X; break;
            case 'Y': ax[i] = Axis::Y; break;
            case 'Z': ax[i] = Axis::Z; break;
            default: return std::nullopt;
        }
    }
    return euler_order_from_axes(ax[0], ax[1], ax[2]);
}

std::string to_string(EulerOrder order) {
    static const char names[] = "XYZ";
    std::string out;
    for (Axis a : axes_of(order)) out += names[index(a)];
    return out;
}

Mat3 axis_rotation(Axis axis, double angle) {
    const Vec3 unit = Vec3::Unit(index(axis));
    return Eigen::AngleAxisd(angle, unit).toRotationMatrix();
}

Mat3 euler_to_matrix(const Vec3& angles, EulerOrder order) {
    const auto ax = axes_of(order);
    return axis_rotation(ax[0], angles[0]) * axis_rotation(ax[1], angles[1]) * axis_rotation(ax[2], angles[2]);
}

Quat euler_to_quat(const Vec3& angles, EulerOrder order) {
    const auto ax = axes_of(order);
    const Quat q = Eigen::AngleAxisd(angles[0], Vec3::Unit(index(ax[0]))) *
                   Eigen::AngleAxisd(angles[1], Vec3::Unit(index(ax[1]))) *
                   Eigen::AngleAxisd(angles[2], Vec3::Unit(index(ax[2])));
    return q.normalized();
}

Vec3 matrix_to_euler(const Mat3& r, EulerOrder order) {
    const auto ax = axes_of(order);
    const int i = index(ax[0]), j = index(ax[1]), k = index(ax[2]);
    const double s = parity(ax);
    // For R = R_i(a) R_j(b) R_k(c): R(i,k) = s·sin b, R(i,i) = cos b cos c, R(i,j) = -s cos b sin c,
    // R(k,k) = cos a cos b, R(j,k) = -s sin a cos b.
    const double cos_b = std::hypot(r(i, i), r(i, j));
    const double b = std::atan2(s * r(i, k), cos_b);
    double a, c;
    if (cos_b > 1e-12) {
        a = std::atan2(-s * r(j, k), r(k, k));
        c = std::atan2(-s * r(i, j), r(i, i));
    } else {
        // Gimbal lock: only a ± c is determined; put it all in a (c = 0, R = R_i(a) R_j(b)).
        a = std::atan2(s * r(k, j), r(j, j));
        c = 0.0;
    }
    return {a, b, c};
}

Vec3 unwrap_angles(const Vec3& angles, const Vec3& near) {
    return {wrap_near(angles[0], near[0]), wrap_near(angles[1], near[1]), wrap_near(angles[2], near[2])};
}

Vec3 matrix_to_euler_near(const Mat3& rotation, EulerOrder order, const Vec3& near) {
    return matrix_to_euler_near(rotation, order, near, Vec3::Ones());
}

Vec3 matrix_to_euler_near(const Mat3& rotation, EulerOrder order, const Vec3& near, const Vec3& weights) {
    const Vec3 first = matrix_to_euler(rotation, order);
    // The other family of solutions: (a + π, π - b, c + π).
    const Vec3 second(first[0] + kPi, kPi - first[1], first[2] + kPi);
    const Vec3 u1 = unwrap_angles(first, near);
    const Vec3 u2 = unwrap_angles(second, near);
    const double d1 = (u1 - near).cwiseAbs2().dot(weights);
    const double d2 = (u2 - near).cwiseAbs2().dot(weights);
    return d1 <= d2 ? u1 : u2;
}

Quat exp_map(const Vec3& v) {
    const double angle = v.norm();
    if (angle < 1e-12) {
        // Second-order series keeps the map smooth and exact to double precision near zero.
        Quat q(1.0 - angle * angle / 8.0, 0.5 * v.x(), 0.5 * v.y(), 0.5 * v.z());
        return q.normalized();
    }
    return Quat(Eigen::AngleAxisd(angle, v / angle));
}

Vec3 log_map(const Quat& rotation) {
    Quat q = rotation.normalized();
    if (q.w() < 0.0) q.coeffs() = -q.coeffs();  // same rotation, angle in [0, π]
    const double sin_half = q.vec().norm();
    if (sin_half < 1e-12) return 2.0 * q.vec();  // first-order, exact to double precision here
    const double angle = 2.0 * std::atan2(sin_half, q.w());
    return q.vec() * (angle / sin_half);
}

Vec3 log_map_near(const Quat& rotation, const Vec3& near) {
    const Vec3 principal = log_map(rotation);
    // A rotation more than π/2 from the neighbour is a discontinuity (in captured data, a glitch):
    // there is no continuity to keep, and following a far branch would leave the track at a large
    // norm where the map is nearly singular. Restart on the principal branch.
    if (angle_between(exp_map(near), rotation) > kPi / 2) return principal;
    const double angle = principal.norm();
    if (angle < 1e-12) {
        // Identity: candidates are 2πk along any axis; the one nearest `near` lies along near's axis.
        const double n = near.norm();
        if (n < kPi) return principal;
        const double k = std::round(n / kTwoPi);
        return principal + near / n * (k * kTwoPi);
    }
    const Vec3 axis = principal / angle;
    // Equivalent vectors are (angle + 2πk)·axis for any integer k (negative k flips the axis sign).
    // Project `near` onto the axis and choose the k closest along it.
    const double along = near.dot(axis);
    const double k = std::round((along - angle) / kTwoPi);
    return axis * (angle + k * kTwoPi);
}

Vec3 swing_twist_log(const Quat& rotation, const Vec3& near) {
    const Quat q = rotation.normalized();
    const double norm = std::hypot(q.w(), q.y());
    double psi = 0.0;
    Quat twist = Quat::Identity();
    if (norm > 1e-12) {  // otherwise upside down: a half turn about a horizontal axis, twist undefined
        psi = 2.0 * std::atan2(q.y(), q.w());
        twist = Quat(q.w() / norm, 0.0, q.y() / norm, 0.0);
    }
    psi = wrap_near(psi, near.y());
    const Vec3 swing = log_map(q * twist.conjugate());
    return {swing.x(), psi, swing.z()};
}

Quat swing_twist_exp(const Vec3& v) {
    return (exp_map(Vec3(v.x(), 0.0, v.z())) * Eigen::AngleAxisd(v.y(), Vec3::UnitY())).normalized();
}

double angle_between(const Quat& a, const Quat& b) {
    const Quat rel = a.conjugate() * b;
    const double s = rel.vec().norm();
    return 2.0 * std::atan2(s, std::abs(rel.w()));
}

}  // namespace mocapdb
