#pragma once
// Internal (not installed): the operator of Kriging::weights (one query at a time) in the form its AVX2 +
// FMA kernels read, built once by Kriging::build. The target is <= 1 us per query at N = 92,
// P = 4 for every variogram model.
//
// 1. The kernel weights b = -Wc gamma(c) + V g_k(c). A query costs one vector of variogram values plus
//    this matrix-vector product with the M by (M + K) operator [-Wc, V]. At M = 92 the full operator
//    (71 KB) does not fit the 32 KB L1 data cache and Eigen's GEMV is bound by the L2 bandwidth (~31
//    bytes per cycle: 0.62 us). -Wc is symmetric: its lower block triangle is half the bytes (35 KB) and
//    each loaded element feeds two FMAs (y_I += A_IJ x_J and y_J += A_IJ^T x_I), which makes the product
//    bound by the two FMA pipes instead (measured 0.34 us at M = 92: 4.3 cycles per 4 by 4 block,
//    against 4).
// 2. The projection w = b + G D (g(c) - G^T b) onto the constraints G^T w = g(c), G = [1, U] the trend
//    basis at the samples: K dot products in one pass over b and the update in a second (Eigen's
//    separate reductions and updates took ~0.1 us). For GLS / OK it corrects rounding errors only; for
//    OLS (where 1^T b = 1) it is also the paper's trend correction U (g_u(c) - U^T b).
//
// Vectors are padded to a multiple of 4 entries (matrices with zero rows), so every load is a full
// 4-wide vector. Only compiled with AVX2 and FMA (the default -march=native build on x86-64); without
// them Kriging::weights keeps the Eigen operator product. The tests compare Kriging::weights (this path)
// with Kriging::weights_batch (one Eigen product with the full operator, then the projection by Eigen).
#if defined(__AVX2__) && defined(__FMA__)
#define MOCAPDB_KRIGING_QUERY_KERNELS 1

#include <Eigen/Core>

namespace mocapdb::kriging::detail {

/// M rounded up to a multiple of 4.
inline Eigen::Index padded_size(Eigen::Index m) { return (m + 3) / 4 * 4; }

/// The lower block triangle of the symmetric sign * a (M by M): blocks (I, J), J <= I, of 4 by 4 (rows
/// and columns past M zero), row block after row block, each block as its 4 rows of 4 doubles.
Eigen::VectorXd pack_symmetric(const Eigen::Ref<const Eigen::MatrixXd>& a, double sign = 1.0);

/// y = A x + T g. packed: pack_symmetric(A), A M by M; t: padded_size(M) by K, column-major, rows past
/// M zero; x: padded_size(M) finite values (the entries past M are multiplied by 0); g: K values; y:
/// padded_size(M) values (the entries past M come out 0). x, g and y must not overlap.
void packed_symmetric_product(const Eigen::VectorXd& packed, const Eigen::MatrixXd& t, const double* x, const double* g,
                              double* y);

struct QueryOperator {
    Eigen::Index m = 0;          ///< unique control points
    Eigen::VectorXd kernel;      ///< pack_symmetric(Wc, -1)
    Eigen::MatrixXd trend;       ///< V (M by K_k) with rows padded to padded_size(M)
    Eigen::MatrixXd basis;       ///< G = [1, U] (M by K) with rows padded to padded_size(M)
    Eigen::VectorXd basis_sums;  ///< K: the column sums of basis as stored (M, then 0 up to rounding)

    /// wc: Wc (M by M, exactly symmetric); v: M by K_k; g: M by K, orthogonal columns, the first 1.
    QueryOperator(const Eigen::Ref<const Eigen::MatrixXd>& wc, const Eigen::Ref<const Eigen::MatrixXd>& v,
                  const Eigen::Ref<const Eigen::MatrixXd>& g);

    Eigen::Index padded_size() const { return basis.rows(); }
    Eigen::Index basis_size() const { return basis.cols(); }

    /// The weights at one query. gamma: padded_size() values, gamma(c) then zeros; g: the K values g(c)
    /// (its first K_k are the kernel's g_k(c)); b: padded_size() values of scratch; corr: K values of
    /// scratch; w: M values (may be b).
    void weights(const double* gamma, const double* g, double* b, double* corr, double* w) const;
};

}  // namespace mocapdb::kriging::detail

#endif
