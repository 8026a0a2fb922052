#pragma once
// What the files of the HOSVD share (internal to the tensor module): the dense kernels (Eigen
// products in fixed blocks on the machine's cores, OpenBLAS's level-3 calls, re-orthonormalization;
// dense_kernels.cpp), the sample-mode basis from the samples' row Gram (sample_basis.cpp), the
// eigenbasis in a Gram's own storage (gram_eigenbasis.cpp) and the chunked projections on the dof and
// time bases (hosvd_projection.cpp). Every result is independent of the number of threads.
#include <algorithm>
#include <cmath>
#include <functional>
#include <string>

#include "mocapdb/core/parallel_tasks.hpp"
#include "mocapdb/core/tensor3.hpp"
#include "mocapdb/core/types.hpp"

namespace mocapdb::tensor::detail {

inline std::string idx(Eigen::Index v) { return std::to_string(v); }

// A Tucker model's fit, 1 - ||A - A_hat|| / ||A||, from ||A||^2 and its core's ||G||^2 (orthonormal bases).
inline double fit_from(double squared_norm_a, double squared_norm_core) {
    if (squared_norm_a <= 0.0) return 1.0;
    return 1.0 - std::sqrt(std::max(0.0, 1.0 - squared_norm_core / squared_norm_a));
}

/// The full symmetric matrix of a lower triangle.
MatX symmetrized(const MatX& lower);

// gram_eigenbasis's sign convention: each column's largest-magnitude entry positive. The columns of
// `companion` (when given, as many as u's) change sign with u's.
void make_signs_canonical(MatX& u, MatX* companion = nullptr);

// The Eigen products of the sample-basis computation on the machine's cores. Every product
// is cut into blocks of a fixed size (not a function of the thread count) and each block is one Eigen
// product, so the values do not depend on how many threads ran them. (The largest operations go to
// OpenBLAS instead: see lower_gram below.)
constexpr Eigen::Index kProductBlock = 512;

// f(first, count) for each block [first, first + count) of kProductBlock indices out of [0, size),
// the blocks on the machine's cores.
template <class F>
void for_each_block(Eigen::Index size, F f) {
    run_parallel_tasks(static_cast<std::size_t>((size + kProductBlock - 1) / kProductBlock), [&](std::size_t i) {
        const Eigen::Index first = static_cast<Eigen::Index>(i) * kProductBlock;
        f(first, std::min(kProductBlock, size - first));
    });
}

// out = a * b, by blocks of a's rows (out's rows).
void parallel_product_by_rows(const Eigen::Ref<const MatX>& a, const Eigen::Ref<const MatX>& b, Eigen::Ref<MatX> out);
// out = a^T * b, by blocks of b's columns (out's columns).
void parallel_transposed_product_by_columns(const Eigen::Ref<const MatX>& a, const Eigen::Ref<const MatX>& b,
                                            Eigen::Ref<MatX> out);

// Lower triangle of a a^T (a: k by n), or of a^T a (a: n by k) when `rows`, into g (resized to k by k;
// its upper triangle is not written). OpenBLAS's dsyrk.
void lower_gram(const Eigen::Ref<const MatX>& a, bool rows, MatX& g);
// out = a^T b (out sized a.cols() by b.cols()): OpenBLAS's dgemm.
void transposed_product(const Eigen::Ref<const MatX>& a, const Eigen::Ref<const MatX>& b, MatX& out);
// v u^-1 in place (u upper triangular, as many columns as v): OpenBLAS's dtrsm.
void solve_upper_on_right(const MatX& u, MatX& v);

// Orthonormal columns from nearly orthonormal ones, keeping the nested spans (column j stays in the
// span of columns 0..j): Cholesky-QR, Householder QR if the Gram is not positive definite. One pass
// leaves an orthogonality error of about eps cond(v)^2, so a second pass runs only when v was not
// already close to orthonormal (||v^T v - I||_F > 0.1, i.e. cond(v)^2 > 1.22; #16: a pass is 5.6 s
// for 11 070 x 3 719). Returns the upper triangular r with v_new = v_old r^-1, or an empty matrix
// when the Householder fallback ran.
MatX reorthonormalize(MatX& v);

// gram_eigenbasis(g) in g's own storage when dsyevd takes it (the same call on the same matrix, so
// the same values bit for bit; columns reversed and signs fixed in place; #16: no second 0.11 GB
// matrix at 3 720): g becomes the eigenvectors, decreasing. False when gram_eigenbasis would use
// Eigen (g untouched), and when LAPACK fails (g overwritten: `overwritten` is set).
bool eigenbasis_in_place(MatX& g, VecX& out_eigenvalues, bool& overwritten);

// Right singular vectors of m (L by N) from the eigendecomposition of m m^T (L by L), or, when m's
// energy lies in a subspace of dimension k <= L / 2 up to `budget`, of b b^T (k by k) with m ~ q b
// (randomized_range): v_j = m^T w_j / sigma_j for the eigenvalues above kKeptEigenvalue * the
// largest (at most min(N, L) columns). out_eigenvalues: N values, decreasing, zeros beyond.
// `owner`, when given, is the matrix m views: released as soon as m is no longer read (after the
// randomized range, or after v = m^T w; #16: the projected samples are 0.3 GB at 10 000 samples).
// out_coordinates, when given, receives m v (L by the columns of v) from the factors: m v = w sigma
// r^-1 (q w sigma r^-1 on the reduced path), r from the re-orthonormalization; by a product with m
// when that fell back to Householder (with `owner` released, m is first rebuilt into it by
// `rebuild_owner`, which must then be given).
MatX right_basis_from_row_gram(const Eigen::Ref<const MatX>& m, double budget, VecX& out_eigenvalues,
                               MatX* owner = nullptr, MatX* out_coordinates = nullptr, bool* out_reduced = nullptr,
                               const std::function<void(MatX&)>& rebuild_owner = nullptr);

// Smallest k whose discarded eigenvalues (tail of the decreasing ev) sum to <= budget (k >= 1).
Eigen::Index kept_for_budget(const VecX& ev, double budget);

// y = a x_0 u0^T x_1 u1^T as an (r0 r1) by N matrix, chunk by chunk on the machine's cores.
MatX projected_dof_time(const Tensor3& a, const Eigen::Ref<const MatX>& u0, const Eigen::Ref<const MatX>& u1);

// core = a x_0 u0^T x_1 u1^T x_2 u2^T, chunk by chunk over the samples: core_(2) is the sum over
// chunks of y_chunk u2(chunk, :), y the dof-and-time projection. The chunks are summed in a fixed
// order whatever the number of threads (two halves of the samples, each accumulated in order, then
// added), so the result does not depend on the machine. Memory: two r0 r1 by r2 sums and a chunk each.
Tensor3 projected_core(const Tensor3& a, const Eigen::Ref<const MatX>& u0, const Eigen::Ref<const MatX>& u1,
                       const Eigen::Ref<const MatX>& u2);

}  // namespace mocapdb::tensor::detail
