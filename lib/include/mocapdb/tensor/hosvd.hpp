#pragma once
// Truncated HOSVD and sequentially truncated HOSVD (ST-HOSVD) of a D by T by N tensor.
//
// Details: docs/headers/tensor.md (mocapdb/tensor/hosvd.hpp).
#include <array>

#include <Eigen/Core>

#include "mocapdb/tensor/tucker.hpp"

namespace mocapdb::tensor {

/// Accumulates the dof and time Gram matrices and the squared norm from sample slices given one at a
/// time (or in chunks of consecutive slices). Memory: D^2 + T^2 doubles.
class GramAccumulator {
public:
    /// dofs (D) >= 1, frames (T) >= 1. Throws InvalidArgument otherwise.
    GramAccumulator(Eigen::Index dofs, Eigen::Index frames);

    /// Adds one sample slice. slice: D by T, all finite. Throws InvalidArgument otherwise.
    void add_slice(const Eigen::Ref<const MatX>& slice);
    /// Adds k >= 0 consecutive slices given side by side: block is D by (T k), slice i in columns
    /// [i T, (i + 1) T) -- the column-major storage of a D by T by k chunk. All finite.
    /// Throws InvalidArgument on a shape mismatch or a non-finite element.
    void add_slices(const Eigen::Ref<const MatX>& block);
    /// Adds the slices of a chunk of consecutive samples. chunk: D by T by k (k >= 0), all finite.
    /// Throws InvalidArgument on a shape mismatch or a non-finite element.
    void add_chunk(const Tensor3& chunk);

    Eigen::Index dofs() const { return dofs_; }
    Eigen::Index frames() const { return frames_; }
    Eigen::Index samples() const { return samples_; }  ///< slices added so far
    double squared_norm() const { return squared_norm_; }

    /// D by D, symmetric: sum_n S_n S_n^T over the slices added so far.
    MatX dof_gram() const;
    /// T by T, symmetric: sum_n S_n^T S_n.
    MatX time_gram() const;

private:
    Eigen::Index dofs_;
    Eigen::Index frames_;
    Eigen::Index samples_ = 0;
    double squared_norm_ = 0.0;
    MatX dof_gram_;   // lower triangle accumulated
    MatX time_gram_;  // lower triangle accumulated
};

/// The mode Gram matrix A_(mode) A_(mode)^T in memory. a: I0 by I1 by I2 (non-empty, finite);
/// mode: 0, 1 or 2. Returns I_mode by I_mode, symmetric. Throws InvalidArgument on bad arguments.
MatX mode_gram(const Tensor3& a, int mode);

/// Eigenbases of the three Gram matrices: everything a truncated HOSVD at any ranks needs.
struct HosvdBases {
    /// U[0]: D by D and U[1]: T by T orthogonal; U[2]: N by K with orthonormal columns, K = N from
    /// the dense sample Gram, K <= min(N, L) from the projected path (the columns that can carry
    /// energy; sample_basis_columns() completes it to any rank). Columns by decreasing eigenvalue.
    std::array<MatX, 3> U;
    ModeSpectra spectra;  ///< the matching eigenvalues (squared singular values), I_n values per mode
    /// The projected path's by-product, else empty: the core at every column of the bases (D by T by
    /// K, hosvd_full_core's shape) from the eigendecomposition's factors instead of a pass over the
    /// data (#16: 7.8 s at 11 070 windows). Equal to hosvd_full_core up to rounding in the dof and
    /// time directions the projection kept, zero in the others (they hold at most the projection's
    /// tolerance of the energy).
    Tensor3 factored_core;
    /// With factored_core: the projected path's dof and time counts k0, k1 (each slice of
    /// factored_core is zero outside its leading k0 x k1 block), and whether U[2] spans the projected
    /// samples (exact Gram of M: up to the eigenvalues below 1e-14 of the largest; false on the
    /// randomized path, whose range may leave out half the tolerance). When it does, the model's terms
    /// over all K columns add up to each sample's projection on the leading k0 dof and k1 time vectors.
    Eigen::Index projected_dofs = 0;
    Eigen::Index projected_frames = 0;
    bool spans_projected_samples = false;
};

/// How hosvd_bases computes the sample basis.
enum class SampleBasisMethod {
    Auto,       ///< Projected when N > L (see the header comment), Dense otherwise
    Dense,      ///< eigendecomposition of the N by N sample Gram
    Projected,  ///< from the L by L Gram of the projected samples (any N)
};

struct HosvdOptions {
    /// Samples per chunk when accumulating the dof and time Gram matrices (>= 1).
    Eigen::Index chunk_samples = 16;
    SampleBasisMethod sample_basis = SampleBasisMethod::Auto;
    /// Projected path: dof and time energy left out of the projection, relative to ||A||^2 (>= 0, < 1e-6).
    double projection_tolerance = 1e-13;
};

/// Eigendecomposition of symmetric Gram matrix g (I by I, lower triangle read). Returns the I by I
/// orthogonal eigenvector matrix, columns by decreasing eigenvalue, each column's largest-magnitude
/// entry made positive; out_eigenvalues: I entries, decreasing, clamped at 0.
MatX gram_eigenbasis(const Eigen::Ref<const MatX>& g, VecX& out_eigenvalues);

/// Full bases of the three modes. a: D by T by N, non-empty, finite.
/// Throws InvalidArgument on bad arguments.
HosvdBases hosvd_bases(const Tensor3& a, const HosvdOptions& options = {});

/// Leading left singular vectors of the sample unfolding of b (I0 by I1 by N, finite): N by `rank`
/// orthonormal columns, by decreasing singular value (each column's largest-magnitude entry
/// positive). From the N by N Gram when N <= I0 I1, else from the I0 I1 by I0 I1 Gram of the other
/// side and a projection (columns beyond the numerical rank completed orthonormally).
/// out_eigenvalues: N squared singular values, decreasing (zeros beyond min(N, I0 I1)).
/// 1 <= rank <= N. Throws InvalidArgument on bad arguments.
MatX sample_mode_basis(const Tensor3& b, Eigen::Index rank, VecX& out_eigenvalues);

/// The first `rank` columns of a sample basis u (N by K, orthonormal columns): u's own columns,
/// then (rank > K) an orthonormal completion. 1 <= rank <= N. Throws InvalidArgument otherwise.
MatX sample_basis_columns(const Eigen::Ref<const MatX>& u, Eigen::Index rank);

/// Bases and spectra from Gram matrices accumulated elsewhere (for instance streamed).
/// dof_gram: D by D; time_gram: T by T; sample_gram: N by N (all symmetric, lower triangles read);
/// squared_norm: ||A||_F^2. Throws InvalidArgument on non-square inputs.
HosvdBases hosvd_bases_from_grams(const Eigen::Ref<const MatX>& dof_gram, const Eigen::Ref<const MatX>& time_gram,
                                  const Eigen::Ref<const MatX>& sample_gram, double squared_norm);

/// Truncated HOSVD from precomputed bases: U_n = first ranks[n] columns of bases.U[n] (the sample
/// basis completed by sample_basis_columns when it has fewer),
/// core = a x_0 U_0^T x_1 U_1^T x_2 U_2^T, error_bound = hosvd_error_bound(bases.spectra, ranks).
/// a: D by T by N, the tensor the bases came from; 1 <= ranks[n] <= dims[n].
/// Throws InvalidArgument on bad arguments.
TuckerModel hosvd_from_bases(const Tensor3& a, const HosvdBases& bases, const Ranks& ranks);

/// The core at every column of the bases: a x_0 U_0^T x_1 U_1^T x_2 U_2^T with the whole of
/// bases.U (D by T by K, K = bases.U[2].cols()). A truncated HOSVD at ranks with ranks[2] <= K has
/// the leading ranks[0] x ranks[1] x ranks[2] block of it as its core (hosvd_from_core), so a rank
/// search projects the data once instead of once per probe. Computed over chunks of samples,
/// on the machine's cores: memory D T K doubles plus a few chunks, no tensor of a's size.
/// a: D by T by N, the tensor the bases came from. Throws InvalidArgument on a shape mismatch.
Tensor3 hosvd_full_core(const Tensor3& a, const HosvdBases& bases);

/// Truncated HOSVD at ranks from full_core = hosvd_full_core(a, bases): the model hosvd_from_bases
/// gives (same bases, fit, error bound; the core up to rounding), without touching a.
/// 1 <= ranks[n] <= dims[n] and ranks[2] <= full_core.dimension(2). Throws InvalidArgument otherwise.
TuckerModel hosvd_from_core(const HosvdBases& bases, const Tensor3& full_core, const Ranks& ranks);

/// The same model, taking the bases' storage instead of copying their leading columns (#16: the
/// N x R3 sample basis is 0.29 GB at 11 070 windows). full_core may be bases.factored_core: its block
/// is copied before anything is released. bases is left empty. Same arguments and errors.
TuckerModel hosvd_from_core(HosvdBases&& bases, const Tensor3& full_core, const Ranks& ranks);

/// Truncated HOSVD at ranks (R1, R2, R3). a: D by T by N, non-empty, finite; 1 <= ranks[n] <= dims[n].
/// Returns a model with method Hosvd, status Ok. Throws InvalidArgument on bad arguments.
TuckerModel hosvd(const Tensor3& a, const Ranks& ranks, const HosvdOptions& options = {});

/// Sequentially truncated HOSVD (Vannieuwenhoven, Vandebril, Meerbergen 2012): for each mode in
/// `order` (a permutation of 0, 1, 2), the basis is taken from the Gram matrix of the tensor already
/// projected on the previous modes' bases, and the tensor is projected at once. Cheaper than HOSVD;
/// its error is at most the HOSVD bound. a and ranks as for hosvd(). Throws InvalidArgument on bad
/// arguments (including an order that is not a permutation).
TuckerModel st_hosvd(const Tensor3& a, const Ranks& ranks, const std::array<int, 3>& order = {0, 1, 2});

}  // namespace mocapdb::tensor
