#pragma once
// The per-sample PCA baseline: each of the N samples of a D by T by N tensor flattened to one
// vector of length D T (its D by T slice in column-major order), the mean subtracted, and the
// N by D T data matrix approximated by k principal components:
//     x_n ~ mean + B_k c_n,   B_k: D T by k orthonormal, c_n = B_k^T (x_n - mean).
// Stored (float32): the mean (D T), the basis (k D T) and the coefficients (N k):
//     bytes(k) = 4 (D T + k D T + N k).
// The fit uses the N by N Gram matrix of the centred samples when N < D T (eigenvectors V, then
// B = orthonormalized X0 V, which keeps the nested order of the components), the D T by D T
// covariance otherwise; it is done once, and reconstruct(k) for any k costs one D T by k by N product.
#include <cstddef>

#include "mocapdb/core/types.hpp"
#include "mocapdb/core/tensor3.hpp"

namespace mocapdb::compression::codecs {

class SamplePca {
public:
    /// Fits every component. a: D by T by N, non-empty, finite. Throws InvalidArgument otherwise.
    explicit SamplePca(const Tensor3& a);

    Eigen::Index dofs() const { return dofs_; }
    Eigen::Index frames() const { return frames_; }
    Eigen::Index samples() const { return samples_; }
    /// Largest k: min(N, D T). At k = N - 1 (or N) the reconstruction is exact up to rounding.
    Eigen::Index max_components() const { return basis_.cols(); }

    /// Singular values of the centred N by D T data matrix, decreasing: max_components() entries
    /// (square roots of the Gram eigenvalues, clamped at 0).
    const VecX& singular_values() const { return singular_values_; }
    /// ||X0 - X0_k||_F^2 = sum of the squared singular values beyond k (double-precision storage).
    /// 0 <= k <= max_components().
    double discarded_energy(Eigen::Index k) const;

    /// Bytes stored at k components (float32 mean, basis and coefficients): 4 (D T + k D T + N k).
    /// 0 <= k <= max_components(). Throws InvalidArgument otherwise.
    std::size_t stored_bytes(Eigen::Index k) const;

    /// The reconstruction with k components (0 <= k <= max_components()): D by T by N.
    /// float32_storage: round the mean, basis and coefficients to float32 first, i.e. reconstruct
    /// exactly what the stored bytes give (default); false uses the double-precision factors.
    /// Throws InvalidArgument on a bad k.
    Tensor3 reconstruct(Eigen::Index k, bool float32_storage = true) const;

    const VecX& mean() const { return mean_; }            ///< D T
    const MatX& basis() const { return basis_; }          ///< D T by max_components()
    const MatX& coefficients() const { return coeffs_; }  ///< max_components() by N

private:
    void check_k(Eigen::Index k, const char* where) const;
    Eigen::Index dofs_ = 0, frames_ = 0, samples_ = 0;
    VecX mean_;
    MatX basis_;
    MatX coeffs_;
    VecX singular_values_;
};

}  // namespace mocapdb::compression::codecs
