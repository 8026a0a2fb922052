#pragma once
// Internal (not installed): the preparation of control points that Kriging::build and
// RbfInterpolator::build share, and its inverse on weights.
//
//   1. the coordinates are checked (N by P, N >= 1, P >= 1, finite);
//   2. coincident points (distance <= tolerance, grouped transitively) are merged into one point (the
//      group's first member) or, without merging, every sample stays its own point (the pairs are
//      counted either way);
//   3. the trend basis is built over the resulting M points.
// An interpolator then works on the M points; `expand_to_samples` maps its weights back to the N
// samples, each point's weight split evenly among the samples merged into it.
#include <Eigen/Core>

#include "mocapdb/kriging/trend.hpp"

namespace mocapdb::kriging::detail {

struct PreparedPoints {
    Eigen::MatrixXd points;            ///< M by P: first member of each group (all N points when not merging).
    Eigen::VectorXi group;             ///< N: index of each sample's point.
    Eigen::VectorXd group_size;        ///< M: samples per point.
    Eigen::Index duplicate_pairs = 0;  ///< pairs of samples within the tolerance (merged or not).
    bool merged = false;               ///< M < N.
    TrendBasis basis;                  ///< trend basis over `points`.
};

/// Throws InvalidArgument, naming `caller`, unless coords is N by P with N >= 1, P >= 1 and finite.
void validate_coords(const char* caller, const Eigen::Ref<const Eigen::MatrixXd>& coords);

/// Steps 2 and 3 above. coords: N by P, already validated; duplicate_tolerance >= 0; merge: merge the
/// groups (else every sample is its own point); trend, trend_rank_tolerance: see TrendBasis::build.
PreparedPoints prepare_points(const Eigen::Ref<const Eigen::MatrixXd>& coords, double duplicate_tolerance, bool merge,
                              TrendKind trend, double trend_rank_tolerance);

/// Weights of the M points to weights of the N samples: out(i, q) = unique(group(i), q) / group_size(group(i)).
/// group, group_size: of a PreparedPoints; unique: M by Q; out: N by Q (may not alias unique).
void expand_to_samples(const Eigen::VectorXi& group, const Eigen::VectorXd& group_size,
                       const Eigen::Ref<const Eigen::MatrixXd>& unique, Eigen::Ref<Eigen::MatrixXd> out);

}  // namespace mocapdb::kriging::detail
