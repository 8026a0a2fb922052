#pragma once
// Weights that turn pose-vector errors into joint-position errors ("truncation spends its
// error budget in centimetres, not radians").
//
// Details: docs/headers/compression.md (mocapdb/compression/dof_weights.hpp).
#include "mocapdb/core/types.hpp"
#include "mocapdb/motion/skeleton.hpp"

namespace mocapdb::compression {

/// The weights w (D entries, all > 0) of the header comment for `skeleton`'s pose vector. A rotation
/// joint that moves nothing (no joint below it at distance > 0) gets the lever of 1 cm, so its values
/// stay bounded.
VecX position_error_weights(const Skeleton& skeleton);

}  // namespace mocapdb::compression
