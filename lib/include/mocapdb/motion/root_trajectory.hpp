#pragma once
// The path of a clip's motion root (Skeleton::motion_root()) in the world: positions and headings per
// frame. Used by the parameter extractors, foot contacts, gait phases and the pose distance.
// Thread safety: pure functions. Errors: InvalidArgument for an invalid clip (validate(Clip)).
#include "mocapdb/core/types.hpp"
#include "mocapdb/motion/clip.hpp"

namespace mocapdb {

/// Global positions of the motion root, 3 by F, cm.
MatX root_positions(const Clip& clip);
/// Its headings, F, radians about +Y, unwrapped along time; 0 when facing the skeleton's rest forward
/// direction.
VecX root_headings(const Clip& clip);

}  // namespace mocapdb
