#pragma once
// Internal to the compression module: a Tucker model's sample-mode terms in pose space, the shared
// step of SampleReconstruction and the rank search's TruncationReconstruction.
#include "mocapdb/core/tensor3.hpp"
#include "mocapdb/core/types.hpp"

namespace mocapdb::compression::detail {

/// Column j - first of out (D T values, column-major D by T) is U_dof core_j U_time^T for each sample
/// column j in [first, last), core_j the leading dof_basis.cols() x time_basis.cols() block of core's
/// slice j. Slices on the machine's cores; each column is the same two products whatever the thread
/// count. out is resized to D T by last - first.
void core_terms(const Tensor3& core, const Eigen::Ref<const MatX>& dof_basis, const Eigen::Ref<const MatX>& time_basis,
                Eigen::Index first, Eigen::Index last, MatX& out);

}  // namespace mocapdb::compression::detail
