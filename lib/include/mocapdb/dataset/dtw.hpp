#pragma once
// Dynamic time warping and the warp curves built from it.
#include <utility>
#include <vector>

#include "mocapdb/core/types.hpp"

namespace mocapdb::align {

struct DtwPath {
    /// Matched (row, column) index pairs from (0, 0) to (rows − 1, cols − 1), each step advancing
    /// one or both indices by one.
    std::vector<std::pair<Eigen::Index, Eigen::Index>> pairs;
    double total_cost = 0.0;  ///< sum of the matched costs
};

/// The minimum-cost monotone path through a cost matrix (rows: the sample's frames, columns: the
/// reference's frames). `band` limits |row/rows − col/cols| to that fraction (1 = unconstrained).
DtwPath dtw(const Eigen::Ref<const MatX>& cost, double band = 1.0);

/// The warp w(j): for each reference frame j (cols values), the sample frame shown there — the mean
/// of the sample frames the path matches to j — made strictly increasing (slope at least
/// `min_slope` sample frames per reference frame) while keeping w(0) = 0 and w(last) = rows − 1.
VecX warp_from_path(const DtwPath& path, Eigen::Index rows, Eigen::Index cols, double min_slope = 0.1);

/// Linear interpolation of a curve given at 0..n−1 at (fractional) positions x (clamped to the ends).
VecX interpolate(const Eigen::Ref<const VecX>& curve, const Eigen::Ref<const VecX>& x);

}  // namespace mocapdb::align
