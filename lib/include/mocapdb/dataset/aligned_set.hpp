#pragma once
// The time-aligned form of a motion set: pose vectors stacked as a D × T × N tensor, with the warps
// that map aligned time back to each sample's own frames.
#include <string>
#include <vector>

#include "mocapdb/core/types.hpp"
#include "mocapdb/motion/pose_vector.hpp"
#include "mocapdb/core/tensor3.hpp"

namespace mocapdb {

struct AlignedSet {
    std::string method;         ///< "dtw" or "linear"
    std::size_t reference = 0;  ///< reference sample index (dtw)
    /// T by N. warps(t, n) is the (fractional) frame of sample n, counted from the sample's first
    /// frame, shown at aligned frame t. Strictly increasing in t, from 0 to frames_n − 1.
    MatX warps;
    /// D by T by N pose vectors (pose_vector.hpp layout), each sample canonicalized by itself (see
    /// `canonical`; by its initial travel direction, formerly by its first frame's heading), exp-map
    /// branches consistent across samples.
    Tensor3 tensor;
    /// Per dof (D): the normalized tensor is (tensor − mean) / scale.
    VecX mean;
    VecX scale;
    /// Per sample: the canonicalization that was applied (to place a reconstruction back in the world).
    std::vector<Canonicalization> canonical;

    Eigen::Index dofs() const { return tensor.dimension(0); }
    Eigen::Index frames() const { return tensor.dimension(1); }
    Eigen::Index samples() const { return tensor.dimension(2); }

    /// T − 1 by N: warps(t + 1, n) − warps(t, n), the source frames advanced per aligned frame (all
    /// positive). Kriging these gives a synthesized motion its own timing.
    MatX inverse_warp_increments() const;
};

/// Throws InvalidArgument unless the shapes agree, warps are strictly increasing, scales positive,
/// everything finite.
void validate(const AlignedSet& aligned);

}  // namespace mocapdb
