#pragma once
// Internal (not installed): grouping of coincident control points, shared by kriging and RBF.
#include <Eigen/Core>

namespace mocapdb::kriging::detail {

struct DuplicateGroups {
    Eigen::MatrixXd points;       ///< M by P: first member of each group (all N points when not merging).
    Eigen::VectorXi group;        ///< N: group index of each sample.
    Eigen::VectorXd group_size;   ///< M: members per group.
    Eigen::Index pairs = 0;       ///< pairs within the tolerance.
    bool merged = false;          ///< M < N.
};

/// coords: N by P. Points at distance <= tolerance are grouped transitively; with merge == false every
/// point is its own group (pairs is still counted).
DuplicateGroups group_duplicates(const Eigen::Ref<const Eigen::MatrixXd>& coords, double tolerance, bool merge);

}  // namespace mocapdb::kriging::detail
