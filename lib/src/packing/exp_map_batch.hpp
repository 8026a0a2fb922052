#pragma once
// Exponential maps of many rotation vectors at once, for the local poses (internal to the packing
// module): the libm sincos behind mocapdb::exp_map costs about as much as the rest of a local pose
// (it saves and restores the rounding mode on every call). Here the half angle's sine and cosine come
// from a Cody-Waite reduction by π/2 and the Cephes minimax polynomials on [-π/4, π/4] (error about
// 1 ulp), so a quaternion differs from exp_map's by ~1e-16 per component; not bit-identical to it,
// so only for outputs whose contract is "equal to ~1e-15" (LocalPose), never for channel rows (whose
// bits the encoder verified). Pure function, thread-safe, no allocation.
#include "lane4.hpp"

namespace mocapdb::packing::detail {

/// exp_map((x, y, z)) of four rotation vectors (by lane) as quaternion components w, qx, qy, qz, to
/// ~1e-16 per component; angles up to ~1e6 rad.
void exp_maps(Lane4 x, Lane4 y, Lane4 z, Lane4& w, Lane4& qx, Lane4& qy, Lane4& qz);

}  // namespace mocapdb::packing::detail
