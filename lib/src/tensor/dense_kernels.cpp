// The HOSVD's dense kernels (hosvd_internal.hpp).
#include <cmath>
#include <limits>

#include <Eigen/Cholesky>
#include <Eigen/QR>
#include <cblas.h>

#include "hosvd_internal.hpp"

namespace mocapdb::tensor::detail {

MatX symmetrized(const MatX& lower) {
    MatX g = lower;
    g.triangularView<Eigen::StrictlyUpper>() = g.transpose();
    return g;
}

void make_signs_canonical(MatX& u, MatX* companion) {
    for (Eigen::Index j = 0; j < u.cols(); ++j) {
        Eigen::Index imax = 0;
        u.col(j).cwiseAbs().maxCoeff(&imax);
        if (u(imax, j) < 0.0) {
            u.col(j) = -u.col(j);
            if (companion) companion->col(j) = -companion->col(j);
        }
    }
}

// out = a * b, by blocks of a's rows (out's rows).
void parallel_product_by_rows(const Eigen::Ref<const MatX>& a, const Eigen::Ref<const MatX>& b, Eigen::Ref<MatX> out) {
    for_each_block(a.rows(), [&](Eigen::Index first, Eigen::Index count) {
        out.middleRows(first, count).noalias() = a.middleRows(first, count) * b;
    });
}

// out = a^T * b, by blocks of b's columns (out's columns).
void parallel_transposed_product_by_columns(const Eigen::Ref<const MatX>& a, const Eigen::Ref<const MatX>& b,
                                            Eigen::Ref<MatX> out) {
    for_each_block(b.cols(), [&](Eigen::Index first, Eigen::Index count) {
        out.middleCols(first, count).noalias() = a.transpose() * b.middleCols(first, count);
    });
}

// The sample basis's level-3 operations on the projected samples go to OpenBLAS (dsyrk, dtrsm, dgemm),
// on its threads: about twice as fast as Eigen's on two cores at 11 070 x 3 719 for the Gram and the
// solves (#16: 4.0 -> 2.3 s and 3.4 -> 1.6 s). Like dsyevd (gram_eigenbasis, below), dgemm's last
// digits change with OpenBLAS's thread count (OPENBLAS_NUM_THREADS); dsyrk's and dtrsm's did not in a
// check on 1, 2, 3 and 8 threads. mocapdb's own worker count changes no value.

// Sizes beyond BLAS's 32-bit integers stay with Eigen.
constexpr Eigen::Index kBlasMaxSize = std::numeric_limits<int>::max();

// Lower triangle of a a^T (a: k by n), or of a^T a (a: n by k) when `rows`, into g (resized to k by k;
// its upper triangle is not written).
void lower_gram(const Eigen::Ref<const MatX>& a, bool rows, MatX& g) {
    const Eigen::Index k = rows ? a.cols() : a.rows(), n = rows ? a.rows() : a.cols();
    g.resize(k, k);
    if (k == 0) return;
    if (n == 0) {
        g.setZero();
        return;
    }
    if (std::max({k, n, a.outerStride()}) > kBlasMaxSize) {
        g.setZero();
        if (rows) g.selfadjointView<Eigen::Lower>().rankUpdate(a.transpose());
        else g.selfadjointView<Eigen::Lower>().rankUpdate(a);
        return;
    }
    cblas_dsyrk(CblasColMajor, CblasLower, rows ? CblasTrans : CblasNoTrans, static_cast<int>(k), static_cast<int>(n),
                1.0, a.data(), static_cast<int>(a.outerStride()), 0.0, g.data(), static_cast<int>(k));
}

// out = a^T b (out sized a.cols() by b.cols()): OpenBLAS's dgemm, 15-20 % faster than Eigen's products
// in fixed blocks at 11 070 x 3 720 x 3 719 (#16: the sample basis's largest product).
void transposed_product(const Eigen::Ref<const MatX>& a, const Eigen::Ref<const MatX>& b, MatX& out) {
    out.resize(a.cols(), b.cols());
    if (out.size() == 0) return;
    if (a.rows() == 0) {
        out.setZero();
        return;
    }
    if (std::max({a.rows(), a.cols(), b.cols(), a.outerStride(), b.outerStride()}) > kBlasMaxSize) {
        out.noalias() = a.transpose() * b;
        return;
    }
    cblas_dgemm(CblasColMajor, CblasTrans, CblasNoTrans, static_cast<int>(a.cols()), static_cast<int>(b.cols()),
                static_cast<int>(a.rows()), 1.0, a.data(), static_cast<int>(a.outerStride()), b.data(),
                static_cast<int>(b.outerStride()), 0.0, out.data(), static_cast<int>(out.rows()));
}

// v u^-1 in place (u upper triangular, as many columns as v).
void solve_upper_on_right(const MatX& u, MatX& v) {
    if (v.size() == 0) return;
    if (std::max(v.rows(), v.cols()) > kBlasMaxSize) {
        u.triangularView<Eigen::Upper>().solveInPlace<Eigen::OnTheRight>(v);
        return;
    }
    cblas_dtrsm(CblasColMajor, CblasRight, CblasUpper, CblasNoTrans, CblasNonUnit, static_cast<int>(v.rows()),
                static_cast<int>(v.cols()), 1.0, u.data(), static_cast<int>(u.rows()), v.data(),
                static_cast<int>(v.rows()));
}

namespace {

// Frobenius norm of g - I, g symmetric and given by its lower triangle.
double distance_from_identity(const MatX& g) {
    double off = 0.0, diagonal = 0.0;
    for (Eigen::Index j = 0; j < g.cols(); ++j) {
        diagonal += (g(j, j) - 1.0) * (g(j, j) - 1.0);
        off += g.col(j).tail(g.rows() - j - 1).squaredNorm();
    }
    return std::sqrt(diagonal + 2.0 * off);
}

}  // namespace

MatX reorthonormalize(MatX& v) {
    MatX r;
    for (int pass = 0; pass < 2; ++pass) {
        MatX g = MatX::Zero(v.cols(), v.cols());
        lower_gram(v, true, g);
        const bool last = distance_from_identity(g) <= 0.1;
        // Factored in g's own storage, U = L^T then copied into its upper triangle (#16: the
        // factor, U and r were three more K x K matrices, 0.33 GB at K = 3 719).
        const Eigen::LLT<Eigen::Ref<MatX>, Eigen::Lower> llt(g);
        if (llt.info() != Eigen::Success) {
            const Eigen::HouseholderQR<MatX> qr(v);
            MatX q = qr.householderQ() * MatX::Identity(v.rows(), v.cols());
            for (Eigen::Index j = 0; j < v.cols(); ++j)
                if (q.col(j).dot(v.col(j)) < 0.0) q.col(j) = -q.col(j);
            v = std::move(q);
            return MatX();
        }
        // v U^-1 (U^T U = v^T v).
        MatX& u = g;
        for (Eigen::Index j = 1; j < u.cols(); ++j) u.col(j).head(j) = u.row(j).head(j).transpose();
        u.triangularView<Eigen::StrictlyLower>().setZero();
        solve_upper_on_right(u, v);
        if (pass == 0) r = std::move(u);
        else r = MatX(u.triangularView<Eigen::Upper>() * r);
        if (last) break;
    }
    return r;
}

}  // namespace mocapdb::tensor::detail
