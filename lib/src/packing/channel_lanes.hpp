#pragma once
// A joint's rotation projected onto its rotation channels, four joints at a time, for the local poses
// (internal to the packing module). ChannelWriter::channel_rotation does it one joint at a time; on the
// 31-joint ASF rig (10 joints with two channels, 10 with one) that was a third of a local pose.
//
// One channel: the twist about the channel's axis C·e, (w, (v·u) u) normalized.
//
// Two channels: channel_rotation goes through a rotation matrix, two half-angle factors and the
// bone-axis sandwiches C⁻¹ · R · C and C · q · C⁻¹. Here each joint's exp-map vector v is first
// turned into its Euler frame, A v with A = s · P · C⁻¹ (C⁻¹ undoes the bone axis, P lists the
// order's axes first, second, third, s = the order's parity), so that exp(A v) is the joint's
// rotation in a frame where its order is x, y, z with parity +1 and its angles are s times the
// source's: the matrix entries and half angles come out in fixed places, four lanes in one vector,
// and the kept angles' factors combine with the axes s · C · e (rows of A) instead of a sandwich. A
// lane whose absent angle's cosine or cos b is within 1e-5 of 0 (where channel_rotation forms Euler
// angles) is reported, not computed.
//
// Each lane computes what channel_rotation computes, to rounding (~1e-16; the result may be the other
// sign of the same rotation). Pure functions, thread-safe, no allocation.
#include "lane4.hpp"
#include "mocapdb/core/types.hpp"

namespace mocapdb::packing::detail {

/// Four joints with one rotation channel: their axes C·e by component.
struct OneChannelLanes {
    Lane4 axis[3]{};
};

/// The twists of rotations (w, x, y, z by lane) about their lanes' axes.
void project_one_channel(const OneChannelLanes& lanes, Lane4 w, Lane4 x, Lane4 y, Lane4 z, Lane4& out_w, Lane4& out_x,
                         Lane4& out_y, Lane4& out_z);

/// Four joints with exactly two rotation channels (a lane without a joint: any values).
struct TwoChannelLanes {
    Lane4 missing{};    ///< index (0, 1, 2) in the order of each lane's absent axis
    Lane4 first[3]{};   ///< s · C · e of the first kept axis, by component (row of A)
    Lane4 second[3]{};  ///< the same for the second kept axis
    Lane4 cross[3]{};   ///< first × second
    Lane4 dot{};        ///< first · second (0 to rounding)
};

/// A = s · P · C⁻¹ for a joint of rotation order `axes` (0 = x, 1 = y, 2 = z), parity s and bone axis C.
Mat3 euler_frame(const int* axes, double parity, const Quat& axis);

/// Sets lane `lane` of `lanes` for a joint whose Euler frame is `a` (euler_frame) and whose absent axis is
/// `missing` (index in the order).
void set_lane(TwoChannelLanes& lanes, int lane, const Mat3& a, int missing);

/// w, x, y, z: exp(A v) of each lane's joint. Writes the projected rotations' components to out_w,
/// out_x, out_y, out_z; returns a mask (bit l for lane l) of lanes left for channel_rotation.
unsigned project_two_channels(const TwoChannelLanes& lanes, Lane4 w, Lane4 x, Lane4 y, Lane4 z, Lane4& out_w,
                              Lane4& out_x, Lane4& out_y, Lane4& out_z);

}  // namespace mocapdb::packing::detail
