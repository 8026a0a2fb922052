#include "channel_lanes.hpp"

#include <cmath>
#include <cstdint>

namespace mocapdb::packing::detail {
namespace {

typedef std::int64_t Mask4 __attribute__((vector_size(32)));

inline Lane4 abs4(Lane4 v) {
    return reinterpret_cast<Lane4>(reinterpret_cast<Mask4>(v) & Mask4{INT64_MAX, INT64_MAX, INT64_MAX, INT64_MAX});
}

// std::copysign(magnitude, sign) lane by lane.
inline Lane4 copysign4(Lane4 magnitude, Lane4 sign) {
    const Mask4 bit{INT64_MIN, INT64_MIN, INT64_MIN, INT64_MIN};
    return reinterpret_cast<Lane4>((reinterpret_cast<Mask4>(abs4(magnitude))) | (reinterpret_cast<Mask4>(sign) & bit));
}

// (cos θ/2, sin θ/2) of θ = atan2(y, x), as channel_writer.cpp's half_angle: the half-angle
// direction is (h + x, y) where x >= 0, (|y|, sign(y)·(h − x)) where x < 0; (1, 0) where h = 0.
inline void half_angles(Lane4 x, Lane4 y, Lane4& c, Lane4& s) {
    const Lane4 h = sqrt4(x * x + y * y);
    const Mask4 nonnegative = x >= 0.0;
    const Lane4 a = nonnegative ? h + x : h - x;
    const Mask4 zero = h == 0.0;
    const Lane4 n = zero ? splat(1.0) : sqrt4(a * a + y * y);
    const Lane4 cn = nonnegative ? a / n : abs4(y) / n;
    const Lane4 sn = nonnegative ? y / n : copysign4(a, y) / n;
    c = zero ? splat(1.0) : cn;
    s = zero ? splat(0.0) : sn;
}

}  // namespace

void project_one_channel(const OneChannelLanes& lanes, Lane4 w, Lane4 x, Lane4 y, Lane4 z, Lane4& out_w, Lane4& out_x,
                         Lane4& out_y, Lane4& out_z) {
    const Lane4 s = x * lanes.axis[0] + y * lanes.axis[1] + z * lanes.axis[2];
    const Lane4 n = sqrt4(w * w + s * s);
    const Mask4 zero = n == 0.0;  // a half turn about an axis at right angles: no twist
    const Lane4 safe = zero ? splat(1.0) : n;
    const Lane4 f = s / safe;
    out_w = zero ? splat(1.0) : w / safe;
    out_x = zero ? splat(0.0) : f * lanes.axis[0];
    out_y = zero ? splat(0.0) : f * lanes.axis[1];
    out_z = zero ? splat(0.0) : f * lanes.axis[2];
}

Mat3 euler_frame(const int* axes, double parity, const Quat& axis) {
    const Mat3 inverse = axis.conjugate().toRotationMatrix();
    Mat3 a;
    for (int n = 0; n < 3; ++n) a.row(n) = parity * inverse.row(axes[n]);
    return a;
}

void set_lane(TwoChannelLanes& lanes, int lane, const Mat3& a, int missing) {
    const int first = missing == 0 ? 1 : 0;
    const int second = missing == 2 ? 1 : 2;
    const Vec3 u = a.row(first).transpose(), v = a.row(second).transpose();
    const Vec3 cross = u.cross(v);
    lanes.missing[lane] = missing;
    for (int i = 0; i < 3; ++i) {
        lanes.first[i][lane] = u[i];
        lanes.second[i][lane] = v[i];
        lanes.cross[i][lane] = cross[i];
    }
    lanes.dot[lane] = u.dot(v);
}

unsigned project_two_channels(const TwoChannelLanes& lanes, Lane4 w, Lane4 x, Lane4 y, Lane4 z, Lane4& out_w,
                              Lane4& out_x, Lane4& out_y, Lane4& out_z) {
    // The rotation matrix's entries in the Euler frame (order x, y, z): as Eigen's toRotationMatrix.
    const Lane4 tx = 2.0 * x, ty = 2.0 * y, tz = 2.0 * z;
    const Lane4 twx = tx * w, twy = ty * w, twz = tz * w;
    const Lane4 txx = tx * x, txy = ty * x, txz = tz * x;
    const Lane4 tyy = ty * y, tyz = tz * y, tzz = tz * z;
    const Lane4 m00 = 1.0 - (tyy + tzz), m01 = txy - twz, m02 = txz + twy, m12 = tyz - twx, m22 = 1.0 - (txx + tyy);
    // channel_rotation's (x, y) of the three angles: R = R_x(a) R_y(b) R_z(c).
    const Lane4 cos_b = sqrt4(m00 * m00 + m01 * m01);
    const Lane4 x0 = m22, y0 = -m12, x1 = cos_b, y1 = m02, x2 = m00, y2 = -m01;
    const Mask4 miss0 = lanes.missing == 0.0, miss1 = lanes.missing == 1.0, miss2 = lanes.missing == 2.0;
    const Lane4 xm = miss0 ? x0 : miss1 ? x1 : x2;
    const Lane4 ym = miss0 ? y0 : miss1 ? y1 : y2;
    const Lane4 xa = miss0 ? x1 : x0, ya = miss0 ? y1 : y0;  // the first kept angle (b where a is absent)
    const Lane4 xb = miss2 ? x1 : x2, yb = miss2 ? y1 : y2;  // the second (b where c is absent)
    // The family test: the sign of the absent angle's cosine, unless it or cos b is near 0.
    const Lane4 h = sqrt4(xm * xm + ym * ym);
    const Lane4 cosine = h > 0.0 ? xm / (h > 0.0 ? h : splat(1.0)) : splat(1.0);
    const Mask4 ok = (cos_b > 1e-5) & (abs4(cosine) > 1e-5);
    const Mask4 second = cosine < 0.0;  // the family (a + π, π − b, c + π)
    Lane4 ca, sa, cb, sb;
    half_angles(xa, ya, ca, sa);
    half_angles(xb, yb, cb, sb);
    // Second family: (π − b)/2 swaps cos and sin; (θ + π)/2 maps (c, s) to (−s, c).
    const Lane4 ca2 = second ? (miss0 ? sa : -sa) : ca, sa2 = second ? ca : sa;
    const Lane4 cb2 = second ? (miss2 ? sb : -sb) : cb, sb2 = second ? cb : sb;
    // (ca + sa·u)(cb + sb·v) with u, v the kept axes in the joint's frame.
    const Lane4 ss = sa2 * sb2;
    out_w = ca2 * cb2 - ss * lanes.dot;
    out_x = (ca2 * sb2) * lanes.second[0] + (sa2 * cb2) * lanes.first[0] + ss * lanes.cross[0];
    out_y = (ca2 * sb2) * lanes.second[1] + (sa2 * cb2) * lanes.first[1] + ss * lanes.cross[1];
    out_z = (ca2 * sb2) * lanes.second[2] + (sa2 * cb2) * lanes.first[2] + ss * lanes.cross[2];
    unsigned left = 0;
    for (int l = 0; l < 4; ++l)
        if (ok[l] == 0) left |= 1u << l;
    return left;
}

}  // namespace mocapdb::packing::detail
