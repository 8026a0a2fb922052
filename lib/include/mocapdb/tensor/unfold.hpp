#pragma once
// Mode-n unfolding (matricization) and folding of a 3-way tensor.
//
// Convention (used by every function of the tensor module): modes are numbered 0 (dof), 1 (time),
// 2 (sample). The mode-n unfolding A_(n) of an I0 by I1 by I2 tensor A is the I_n by (I_p * I_q)
// matrix, where p < q are the two other modes, with
//     A_(n)(i_n, i_p + I_p * i_q) = A(i0, i1, i2),
// i.e. the remaining indices in their natural order, the lower mode varying fastest. Concretely:
//     A_(0)(i0, i1 + I1 * i2),   A_(1)(i1, i0 + I0 * i2),   A_(2)(i2, i0 + I0 * i1).
// With Eigen's column-major tensor storage, A_(0) is the storage itself and A_(2) its transpose
// when seen as an (I0 * I1) by I2 matrix.
#include <array>

#include <Eigen/Core>

#include "mocapdb/core/types.hpp"
#include "mocapdb/core/tensor3.hpp"

namespace mocapdb::tensor {

constexpr int kDofMode = 0;
constexpr int kTimeMode = 1;
constexpr int kSampleMode = 2;

/// Sizes of the three modes (I0, I1, I2), e.g. (D, T, N).
using Dims3 = std::array<Eigen::Index, 3>;
/// Multilinear ranks (R1, R2, R3) of a Tucker model, one per mode.
using Ranks = std::array<Eigen::Index, 3>;

/// The dimensions of a: (a.dimension(0), a.dimension(1), a.dimension(2)).
Dims3 dims_of(const Tensor3& a);

/// Human-readable mode name: "dof", "time" or "sample".
const char* mode_name(int mode);

/// Mode-n unfolding (convention above).
/// a: I0 by I1 by I2; mode: 0, 1 or 2.
/// Returns I_mode by (product of the other two dimensions).
/// Throws InvalidArgument when mode is not 0, 1 or 2.
MatX unfold(const Tensor3& a, int mode);

/// Inverse of unfold: fold(unfold(a, n), n, dims_of(a)) == a.
/// m: dims[mode] by (product of the other two dims); mode: 0, 1 or 2; dims: (I0, I1, I2), all >= 0.
/// Returns I0 by I1 by I2.
/// Throws InvalidArgument on a bad mode, negative dims, or when m's shape does not match dims.
Tensor3 fold(const Eigen::Ref<const MatX>& m, int mode, const Dims3& dims);

}  // namespace mocapdb::tensor
