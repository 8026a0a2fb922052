#pragma once
// The n-mode product of a 3-way tensor with a matrix: B = A x_n M, defined by B_(n) = M * A_(n)
// (unfolding convention in unfold.hpp). Computed with one or a few matrix products over the tensor's
// storage; no unfolded copy of A is made.
#include <Eigen/Core>

#include "mocapdb/tensor/unfold.hpp"

namespace mocapdb::tensor {

/// B = A x_mode M.
/// a: I0 by I1 by I2; m: J by I_mode; mode: 0, 1 or 2.
/// Returns the tensor a with dimension `mode` replaced by J (J = 0 gives an empty tensor).
/// Throws InvalidArgument on a bad mode or when m.cols() != I_mode.
Tensor3 mode_product(const Tensor3& a, const Eigen::Ref<const MatX>& m, int mode);

/// B = A x_mode M^T (projection onto the columns of M when they are orthonormal).
/// a: I0 by I1 by I2; m: I_mode by J; mode: 0, 1 or 2.
/// Returns the tensor a with dimension `mode` replaced by J.
/// Throws InvalidArgument on a bad mode or when m.rows() != I_mode.
Tensor3 mode_product_transposed(const Tensor3& a, const Eigen::Ref<const MatX>& m, int mode);

/// Squared Frobenius norm: the sum of the squares of all elements of a (any shape).
double squared_norm(const Tensor3& a);

}  // namespace mocapdb::tensor
