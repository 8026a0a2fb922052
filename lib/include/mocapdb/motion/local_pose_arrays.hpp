#pragma once
// A clip as arrays of local rotations and a root path, and back: what a model predicting
// rotations works with, whatever the rig's channel order or ASF axes. Arrays are C order, frames first:
//   local rotations  F x J unit quaternions (w, x, y, z): joint j's whole local rotation
//                    (Skeleton::local_rotation, C · R(channels) · C⁻¹; identity without channels);
//   root positions   F x 3: joint 0's local translation (its world position), cm.
// forward_kinematics_of_arrays places joint 0 at the root position and every other joint at its rest
// translation: Clip joint positions exactly for rigs whose only position channels are joint 0's.
// channels_from_local_rotations writes channel rows giving those rotations (Euler angles unwrapped
// against the previous frame; a rotation a joint's channels cannot express is projected: missing axes
// dropped), joint 0's position channels from the root positions, other position channels at rest.
// InvalidArgument on a non-finite value or a quaternion far from unit length (|q| outside 0.9..1.1).
#include <cstddef>

#include "mocapdb/core/types.hpp"
#include "mocapdb/motion/clip.hpp"
#include "mocapdb/motion/skeleton.hpp"

namespace mocapdb {

/// F x J x 4 values into out.
void local_rotations_of(const Clip& clip, double* out);
/// F x 3 values into out.
void root_positions_of(const Clip& clip, double* out);
/// World positions F x J x 3 into out from F x J x 4 rotations and F x 3 root positions.
void forward_kinematics_of_arrays(const Skeleton& skeleton, const double* rotations, const double* root_positions,
                                  std::size_t frames, double* out);
/// Channel rows (frames x skeleton.channel_count()) from F x J x 4 rotations and F x 3 root positions.
FrameMatrix channels_from_local_rotations(const Skeleton& skeleton, const double* rotations,
                                          const double* root_positions, std::size_t frames);
/// Unit quaternions (w, x, y, z) of `count` row-major 3 x 3 rotation matrices (InvalidArgument for a
/// matrix that is not a rotation within 1e-3).
void quaternions_of_matrices(const double* matrices, std::size_t count, double* out);
/// A frame row with every channel at rest: position channels at the offset (0 when they add to it),
/// rotations 0.
VecX rest_row(const Skeleton& skeleton);
/// Joint j's rotation channels in `row` for its whole local rotation, Euler angles nearest `near_row`'s.
void write_rotation_channels(const Skeleton& skeleton, std::size_t j, const Quat& local, const double* near_row,
                             double* row);

}  // namespace mocapdb
