#pragma once
// Rotation conversions: Euler angles (the six Tait-Bryan orders BVH uses) <-> quaternion <-> matrix
// <-> exponential map (rotation vector), with branch selection that keeps time series continuous.
#include <array>
#include <optional>
#include <string>
#include <string_view>

#include "mocapdb/core/types.hpp"

namespace mocapdb {

enum class Axis { X = 0, Y = 1, Z = 2 };

/// Composition order of three elemental rotations. For order (a, b, c) the rotation matrix is
/// R = R_a(θ_a) · R_b(θ_b) · R_c(θ_c): the BVH convention, where the channel listed first is the
/// outermost factor (intrinsic rotations about a, then the new b, then the newer c).
enum class EulerOrder { XYZ, XZY, YXZ, YZX, ZXY, ZYX };

/// The three axes of an order, outermost first.
std::array<Axis, 3> axes_of(EulerOrder order);
/// The order whose axes are (a, b, c); nullopt when two axes repeat.
std::optional<EulerOrder> euler_order_from_axes(Axis a, Axis b, Axis c);
/// "XYZ", "ZXY", ... (case-insensitive on input); nullopt for anything else.
std::optional<EulerOrder> euler_order_from_string(std::string_view text);
std::string to_string(EulerOrder order);

/// Rotation by angle (radians) about one coordinate axis (right-handed).
Mat3 axis_rotation(Axis axis, double angle);

/// angles[i] is the angle about axes_of(order)[i], radians.
Mat3 euler_to_matrix(const Vec3& angles, EulerOrder order);
Quat euler_to_quat(const Vec3& angles, EulerOrder order);

/// Principal decomposition: the middle angle lies in [-π/2, π/2], the others in (-π, π].
/// At gimbal lock the last angle is set to 0.
Vec3 matrix_to_euler(const Mat3& rotation, EulerOrder order);
/// Of all Euler triples that produce `rotation` (both solution families, any multiple of 2π per
/// angle), the one closest to `near`: use the previous frame's angles to avoid 360° jumps and flips.
Vec3 matrix_to_euler_near(const Mat3& rotation, EulerOrder order, const Vec3& near);

/// As above, with a weight per angle in the distance: a large weight pins an angle near its `near`
/// value (used for axes a joint has no channel for, which must stay at 0).
Vec3 matrix_to_euler_near(const Mat3& rotation, EulerOrder order, const Vec3& near, const Vec3& weights);

/// Each component shifted by a multiple of 2π to lie within π of the same component of `near`.
Vec3 unwrap_angles(const Vec3& angles, const Vec3& near);

/// Exponential map: rotation vector (axis times angle, radians) to unit quaternion.
Quat exp_map(const Vec3& rotation_vector);
/// Principal logarithm: the rotation vector with angle in [0, π].
Vec3 log_map(const Quat& rotation);
/// The rotation vector for `rotation` closest to `near` among the equivalent ones (angle + 2πk along
/// the axis, both axis signs): keeps exp-map tracks continuous in time and consistent across samples.
/// When `rotation` is more than π/2 away from exp(near) (a discontinuity, not a motion to follow),
/// the principal logarithm is returned instead.
Vec3 log_map_near(const Quat& rotation, const Vec3& near);

/// Heading-relative logarithm for orientations that spin about the vertical (a character's root).
/// The rotation is split as q = S · R_y(ψ): a swing S about a horizontal axis (how far the body's up
/// axis tilts from +Y) after a twist ψ about +Y. Returns (s_x, ψ, s_z) where (s_x, 0, s_z) = log(S)
/// and ψ is unwrapped to within π of near.y(). Unlike log_map_near, this stays continuous through
/// any number of full turns (a plain exponential map must cross the 2π shell, where it is singular);
/// it is singular only when the body is upside down (swing angle π).
Vec3 swing_twist_log(const Quat& rotation, const Vec3& near);
/// Inverse of swing_twist_log.
Quat swing_twist_exp(const Vec3& swing_twist);

/// Angle in [0, π] of the relative rotation a⁻¹·b.
double angle_between(const Quat& a, const Quat& b);

}  // namespace mocapdb
