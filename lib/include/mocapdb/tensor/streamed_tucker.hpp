#pragma once
// A Tucker model of a D × T × N tensor that is never held in memory: the sample slices S_n (D × T)
// are read from a source, twice.
//   pass 1: the dof and time Gram matrices accumulate slice by slice (GramAccumulator); their
//           leading eigenvectors are U_dof (D × R1) and U_time (T × R2), as in the HOSVD;
//   pass 2: each slice is projected, C_n = U_dofᵀ S_n U_time (R1 × R2), and kept (R1 R2 values per
//           sample); the sample basis U_sample (N × R3) holds the leading right singular vectors of
//           M = [vec C_1 … vec C_N] (R1 R2 × N), from the smaller of M Mᵀ and Mᵀ M; the core is
//           M U_sample.
// Memory: D² + T² + R1 R2 N + min(R1 R2, N)² doubles and one slice, instead of D T N.
// The sample mode is truncated after the other two (as in ST-HOSVD), so the error is
//   ‖A − Â‖² = ‖A‖² − ‖G‖² ≤ (dof and time eigenvalues discarded) + (projected sample energy discarded),
// which is the model's error_bound.
#include <functional>

#include "mocapdb/tensor/tucker.hpp"

namespace mocapdb::tensor {

/// Writes sample slice n (0 ≤ n < N) into out (D × T, already sized). Called twice per slice, in
/// order n = 0 … N − 1 each pass; it may read from a file.
using SliceSource = std::function<void(Eigen::Index n, Eigen::Ref<MatX> out)>;

/// dims = (D, T, N), 1 ≤ ranks[n] ≤ dims[n]. The model's method is StHosvd (sequential in the sample
/// mode). Throws InvalidArgument on bad ranks or a non-finite slice value.
TuckerModel streamed_tucker(const SliceSource& source, const Dims3& dims, const Ranks& ranks);

}  // namespace mocapdb::tensor
