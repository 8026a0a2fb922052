#pragma once
// The pose distance used for time alignment.
//
// Each frame is described by its joint positions in the frame's own root heading frame: FK
// positions minus the root's floor position (x, z; height is kept), rotated by −ψ about +Y (ψ the
// root heading). Poses are thus compared whatever the character's location and facing. The distance
// of two frames is the root-mean-square, over joints, of the Euclidean distance between
// corresponding joints [cm]: d(a, b) = sqrt(1/J · Σ_j ‖x_j(a) − x_j(b)‖²).
#include "mocapdb/core/types.hpp"
#include "mocapdb/motion/clip.hpp"

namespace mocapdb::align {

/// Pose features of every frame: 3·J by F (the heading-frame joint positions above).
MatX pose_features(const Clip& clip);

/// Distances between every frame of `a` and every frame of `b` (features as from pose_features,
/// same skeleton): Fa by Fb, cm.
MatX pose_distance_matrix(const Eigen::Ref<const MatX>& a, const Eigen::Ref<const MatX>& b);

/// Distance of two single feature columns, cm.
double pose_distance(const Eigen::Ref<const VecX>& a, const Eigen::Ref<const VecX>& b);

}  // namespace mocapdb::align
