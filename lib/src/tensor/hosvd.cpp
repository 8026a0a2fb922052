#include "mocapdb/tensor/hosvd.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <cblas.h>
#include <lapacke.h>

#include "mocapdb/core/error.hpp"
#include "mocapdb/core/parallel_tasks.hpp"
#include "mocapdb/tensor/mode_product.hpp"

namespace mocapdb::tensor {

namespace {

std::string idx(Eigen::Index v) { return std::to_string(v); }

MatX symmetrized(const MatX& lower) {
    MatX g = lower;
    g.triangularView<Eigen::StrictlyUpper>() = g.transpose();
    return g;
}

double fit_from(double squared_norm_a, double squared_norm_core) {
    if (squared_norm_a <= 0.0) return 1.0;
    return 1.0 - std::sqrt(std::max(0.0, 1.0 - squared_norm_core / squared_norm_a));
}

// gram_eigenbasis's sign convention: each column's largest-magnitude entry positive. The columns of
// `companion` (when given, as many as u's) change sign with u's.
void make_signs_canonical(MatX& u, MatX* companion = nullptr) {
    for (Eigen::Index j = 0; j < u.cols(); ++j) {
        Eigen::Index imax = 0;
        u.col(j).cwiseAbs().maxCoeff(&imax);
        if (u(imax, j) < 0.0) {
            u.col(j) = -u.col(j);
            if (companion) companion->col(j) = -companion->col(j);
        }
    }
}

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

// Frobenius norm of g - I, g symmetric and given by its lower triangle.
double distance_from_identity(const MatX& g) {
    double off = 0.0, diagonal = 0.0;
    for (Eigen::Index j = 0; j < g.cols(); ++j) {
        diagonal += (g(j, j) - 1.0) * (g(j, j) - 1.0);
        off += g.col(j).tail(g.rows() - j - 1).squaredNorm();
    }
    return std::sqrt(diagonal + 2.0 * off);
}

// Orthonormal columns from nearly orthonormal ones, keeping the nested spans (column j stays in the
// span of columns 0..j): Cholesky-QR, Householder QR if the Gram is not positive definite. One pass
// leaves an orthogonality error of about eps cond(v)^2, so a second pass runs only when v was not
// already close to orthonormal (||v^T v - I||_F > 0.1, i.e. cond(v)^2 > 1.22; #16: a pass is 5.6 s
// for 11 070 x 3 719). Returns the upper triangular r with v_new = v_old r^-1, or an empty matrix
// when the Householder fallback ran.
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

// Eigenvalues below this fraction of the largest give no sample-basis column on the projected path:
// M^T w / sigma would be rounding noise there (the dense path's vectors are not resolved either).
constexpr double kKeptEigenvalue = 1e-14;
// Energy (relative) that sample_mode_basis's randomized range may leave out.
constexpr double kKeptEnergy = 1e-13;

// Orthonormal q (L by k) and b = q^T m (k by N) with ||m - q b||^2 = ||m||^2 - ||b||^2 <= budget, by
// the blocked randomized range finder with exact energy accounting (Halko, Martinsson, Tropp 2011;
// Martinsson, Voronin 2016): blocks of m * Gaussian, orthogonalized against the columns found so far
// and rank-revealed (column-pivoted QR), until the energy is accounted for or a probe finds nothing
// new. Deterministic (fixed seed). Returns false when that needs more than max_k columns, or as
// soon as the missing energy's decay says it will (the data has no low numerical rank: the caller
// decomposes m m^T instead).
bool randomized_range(const Eigen::Ref<const MatX>& m, double budget, Eigen::Index max_k, MatX& q, MatX& b) {
    const Eigen::Index l = m.rows(), n = m.cols(), block = 64;
    std::mt19937_64 rng(16);
    std::normal_distribution<double> gauss(0.0, 1.0);
    const double total = m.squaredNorm();
    std::vector<MatX> qs, bs;
    Eigen::Index k = 0;
    double captured = 0.0, previous_missing = total;
    while (total - captured > budget) {
        if (k + block > max_k) return false;
        MatX omega(n, block);
        for (Eigen::Index i = 0; i < omega.size(); ++i) omega.data()[i] = gauss(rng);
        MatX y(l, block);
        parallel_product_by_rows(m, omega, y);
        const double y_norm = y.norm();
        for (int pass = 0; pass < 2; ++pass)
            for (const MatX& qi : qs) y.noalias() -= qi * (qi.transpose() * y);
        Eigen::ColPivHouseholderQR<MatX> qr(y);
        qr.setThreshold(1e-10 * y_norm / std::max(1e-300, y.norm()));
        const Eigen::Index r = qr.rank();
        // Nothing above 1e-10 of the probe's size is left: the range is exhausted (the rest of the
        // missing energy is the rounding of the running sums).
        if (r == 0) break;
        MatX qi = qr.householderQ() * MatX::Identity(l, r);
        for (const MatX& qj : qs) qi.noalias() -= qj * (qj.transpose() * qi);
        const Eigen::HouseholderQR<MatX> clean(qi);
        qi = clean.householderQ() * MatX::Identity(l, r);
        MatX bi(r, n);
        parallel_transposed_product_by_columns(qi, m, bi);
        captured += bi.squaredNorm();
        qs.push_back(std::move(qi));
        bs.push_back(std::move(bi));
        k += r;
        // The missing energy shrinks by a factor per block that grows on real spectra (fast decay
        // first, then a long flat tail). Continuing at the last block's factor, the budget would be
        // reached after `blocks` more blocks; when that passes twice max_k columns, the range would
        // fail anyway: give up now (#16: on 11 070 overlapping windows, sample rank ~3 200 of 3 720,
        // the doomed run to l / 2 took 8.9 s).
        const double missing = total - captured;
        if (missing > budget) {
            const double factor = missing / previous_missing;
            const double blocks = factor < 1.0 ? std::log(budget / missing) / std::log(factor) : HUGE_VAL;
            if (static_cast<double>(k) + blocks * static_cast<double>(r) > 2.0 * static_cast<double>(max_k))
                return false;
        }
        previous_missing = missing;
    }
    q.resize(l, k);
    b.resize(k, n);
    Eigen::Index at = 0;
    for (std::size_t i = 0; i < qs.size(); ++i) {
        q.middleCols(at, qs[i].cols()) = qs[i];
        b.middleRows(at, bs[i].rows()) = bs[i];
        at += qs[i].cols();
        qs[i].resize(0, 0);  // one copy of b at a time, not two (#16: 0.15 GB at 10 000 samples)
        bs[i].resize(0, 0);
    }
    return true;
}

bool eigenbasis_in_place(MatX& g, VecX& out_eigenvalues, bool& overwritten);  // below, beside lapack_eigen

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
                               const std::function<void(MatX&)>& rebuild_owner = nullptr) {
    const Eigen::Index l = m.rows(), n = m.cols();
    MatX q, b;
    const bool reduced = l > 256 && randomized_range(m, budget, l / 2, q, b);
    if (out_reduced) *out_reduced = reduced;
    if (reduced && owner) owner->resize(0, 0);  // m dangles from here on: only b is read
    const Eigen::Index side = reduced ? b.rows() : l;
    if (reduced && !out_coordinates) q.resize(0, 0);
    const auto gram = [&](MatX& c) {
        c = MatX::Zero(side, side);
        lower_gram(reduced ? Eigen::Ref<const MatX>(b) : m, false, c);
    };
    VecX ev;
    MatX w;  // the Gram's eigenvectors (its lower triangle read), by decreasing eigenvalue
    if (side > 0) {
        gram(w);
        bool overwritten = false;
        if (!eigenbasis_in_place(w, ev, overwritten)) {
            if (overwritten) gram(w);
            w = gram_eigenbasis(w, ev);
        }
    }
    const Eigen::Index top = std::min(side, n);
    out_eigenvalues = VecX::Zero(n);
    out_eigenvalues.head(top) = ev.head(top);
    Eigen::Index kept = 0;
    while (kept < top && ev(kept) > 0.0 && ev(kept) > kKeptEigenvalue * ev(0)) ++kept;
    MatX v(n, kept);
    if (kept == 0) return v;
    // v = b^T w (or m^T w).
    {
        const Eigen::Ref<const MatX> src = reduced ? Eigen::Ref<const MatX>(b) : m;
        transposed_product(src, w.leftCols(kept), v);
    }
    // m is not read again unless the re-orthonormalization falls back to Householder: on the exact
    // path its owner goes now, before the Gram of v and the core (#16: 0.33 GB of the peak at 11 070).
    const bool released = !reduced && owner && rebuild_owner && out_coordinates;
    if (released) owner->resize(0, 0);
    v *= ev.head(kept).cwiseSqrt().cwiseInverse().asDiagonal();
    const MatX r = reorthonormalize(v);
    if (!out_coordinates) {
        make_signs_canonical(v);
        return v;
    }
    MatX& coordinates = *out_coordinates;
    if (r.size() > 0) {
        // w sigma r^-1 (then q times it on the reduced path), in w's storage.
        w.conservativeResize(Eigen::NoChange, kept);
        w *= ev.head(kept).cwiseSqrt().asDiagonal();
        solve_upper_on_right(r, w);
        if (reduced) {
            coordinates.resize(l, kept);
            parallel_product_by_rows(q, w, coordinates);
        } else {
            coordinates = std::move(w);
        }
    } else if (reduced) {
        // No triangular factor (Householder ran): the product itself, q b v here, m v below.
        coordinates.noalias() = b * v;
        coordinates = q * coordinates;
    } else if (released) {
        rebuild_owner(*owner);
        coordinates.noalias() = *owner * v;
        owner->resize(0, 0);
    } else {
        coordinates.noalias() = m * v;
    }
    make_signs_canonical(v, &coordinates);
    return v;
}

// Smallest k whose discarded eigenvalues (tail of the decreasing ev) sum to <= budget (k >= 1).
Eigen::Index kept_for_budget(const VecX& ev, double budget) {
    Eigen::Index k = ev.size();
    double tail = 0.0;
    while (k > 1 && tail + ev(k - 1) <= budget) tail += ev(--k);
    return k;
}

// Samples [first, first + count) of a projected on the dof and time bases: column i of out (r0 r1
// by count) is u0^T a(:, :, first + i) u1 in column-major order. The same products, in the same
// order, as mode_product_transposed on modes 0 and 1, without a D by T by N intermediate.
void project_dof_time(const Tensor3& a, const Eigen::Ref<const MatX>& u0t, const Eigen::Ref<const MatX>& u1t,
                      Eigen::Index first, Eigen::Index count, Eigen::Ref<MatX> out) {
    const Eigen::Index d = a.dimension(0), t = a.dimension(1), r0 = u0t.rows(), r1 = u1t.rows();
    MatX dof_side(r0, t * count);
    dof_side.noalias() = u0t * Eigen::Map<const MatX>(a.data() + first * d * t, d, t * count);
    for (Eigen::Index i = 0; i < count; ++i) {
        Eigen::Map<MatX> o(out.col(i).data(), r0, r1);
        o.noalias() = dof_side.middleCols(i * t, t) * u1t.transpose();
    }
}

// Samples per chunk of the chunked projections: a few MB of intermediates at D T = 5 400.
constexpr Eigen::Index kProjectionChunk = 128;

// y = a x_0 u0^T x_1 u1^T as an (r0 r1) by N matrix, chunk by chunk on the machine's cores.
MatX projected_dof_time(const Tensor3& a, const Eigen::Ref<const MatX>& u0, const Eigen::Ref<const MatX>& u1) {
    const Eigen::Index n = a.dimension(2);
    const MatX u0t = u0.transpose(), u1t = u1.transpose();
    MatX y(u0.cols() * u1.cols(), n);
    const auto chunks = static_cast<std::size_t>((n + kProjectionChunk - 1) / kProjectionChunk);
    run_parallel_tasks(chunks, [&](std::size_t c) {
        const Eigen::Index first = static_cast<Eigen::Index>(c) * kProjectionChunk;
        const Eigen::Index count = std::min(kProjectionChunk, n - first);
        project_dof_time(a, u0t, u1t, first, count, y.middleCols(first, count));
    });
    return y;
}

// core = a x_0 u0^T x_1 u1^T x_2 u2^T, chunk by chunk over the samples: core_(2) is the sum over
// chunks of y_chunk u2(chunk, :), y the dof-and-time projection. The chunks are summed in a fixed
// order whatever the number of threads (two halves of the samples, each accumulated in order, then
// added), so the result does not depend on the machine. Memory: two r0 r1 by r2 sums and a chunk each.
Tensor3 projected_core(const Tensor3& a, const Eigen::Ref<const MatX>& u0, const Eigen::Ref<const MatX>& u1,
                       const Eigen::Ref<const MatX>& u2) {
    const Eigen::Index n = a.dimension(2), r0 = u0.cols(), r1 = u1.cols(), r2 = u2.cols();
    const MatX u0t = u0.transpose(), u1t = u1.transpose();
    constexpr std::size_t parts = 2;
    std::array<MatX, parts> partial;
    run_parallel_tasks(parts, [&](std::size_t p) {
        const Eigen::Index begin = n * static_cast<Eigen::Index>(p) / static_cast<Eigen::Index>(parts);
        const Eigen::Index end = n * static_cast<Eigen::Index>(p + 1) / static_cast<Eigen::Index>(parts);
        MatX& acc = partial[p];
        acc = MatX::Zero(r0 * r1, r2);
        MatX y(r0 * r1, std::min(kProjectionChunk, std::max<Eigen::Index>(1, end - begin)));
        for (Eigen::Index first = begin; first < end; first += kProjectionChunk) {
            const Eigen::Index count = std::min(kProjectionChunk, end - first);
            project_dof_time(a, u0t, u1t, first, count, y.leftCols(count));
            acc.noalias() += y.leftCols(count) * u2.middleRows(first, count);
        }
    });
    Tensor3 core(r0, r1, r2);
    Eigen::Map<MatX> c(core.data(), r0 * r1, r2);
    c = partial[0];
    for (std::size_t p = 1; p < parts; ++p) c += partial[p];
    return core;
}

}  // namespace

MatX sample_basis_columns(const Eigen::Ref<const MatX>& u, Eigen::Index rank) {
    const Eigen::Index n = u.rows(), k = u.cols();
    if (rank < 1 || rank > n || k > n) {
        throw InvalidArgument("sample_basis_columns: the rank must be in [1, " + idx(n) + "] for a basis of " + idx(n) +
                              " by " + idx(k) + ", got " + idx(rank));
    }
    if (rank <= k) return u.leftCols(rank);
    MatX out(n, rank);
    out.leftCols(k) = u;
    if (k == 0) {
        out = MatX::Identity(n, rank);
        return out;
    }
    // Columns k..rank-1 of the orthogonal factor of u's Householder QR are orthogonal to span(u).
    const Eigen::HouseholderQR<MatX> qr(u);
    MatX e = MatX::Zero(n, rank - k);
    for (Eigen::Index j = 0; j < rank - k; ++j) e(k + j, j) = 1.0;
    out.rightCols(rank - k).noalias() = qr.householderQ() * e;
    return out;
}

MatX sample_mode_basis(const Tensor3& b, Eigen::Index rank, VecX& out_eigenvalues) {
    check_tensor(b, "sample_mode_basis");
    const Eigen::Index l = b.dimension(0) * b.dimension(1), n = b.dimension(2);
    if (rank < 1 || rank > n)
        throw InvalidArgument("sample_mode_basis: the rank must be in [1, " + idx(n) + "], got " + idx(rank));
    if (n <= l) return gram_eigenbasis(mode_gram(b, 2), out_eigenvalues).leftCols(rank);
    const Eigen::Map<const MatX> m(b.data(), l, n);
    return sample_basis_columns(right_basis_from_row_gram(m, kKeptEnergy * m.squaredNorm(), out_eigenvalues), rank);
}

// ---------------------------------------------------------------------------------------------------
GramAccumulator::GramAccumulator(Eigen::Index dofs, Eigen::Index frames) : dofs_(dofs), frames_(frames) {
    if (dofs < 1 || frames < 1) {
        throw InvalidArgument("GramAccumulator: dofs and frames must be >= 1, got " + idx(dofs) + " and " +
                              idx(frames));
    }
    dof_gram_ = MatX::Zero(dofs, dofs);
    time_gram_ = MatX::Zero(frames, frames);
}

void GramAccumulator::add_slices(const Eigen::Ref<const MatX>& block) {
    if (block.rows() != dofs_ || block.cols() % frames_ != 0) {
        throw InvalidArgument("GramAccumulator::add_slices: the block must be " + idx(dofs_) + " by (" + idx(frames_) +
                              " k), got " + idx(block.rows()) + " by " + idx(block.cols()));
    }
    if (block.size() == 0) return;
    if (!block.allFinite()) throw InvalidArgument("GramAccumulator::add_slices: every element must be finite");
    const Eigen::Index k = block.cols() / frames_;
    dof_gram_.selfadjointView<Eigen::Lower>().rankUpdate(block);
    for (Eigen::Index i = 0; i < k; ++i) {
        time_gram_.selfadjointView<Eigen::Lower>().rankUpdate(block.middleCols(i * frames_, frames_).transpose());
    }
    squared_norm_ += block.squaredNorm();
    samples_ += k;
}

void GramAccumulator::add_slice(const Eigen::Ref<const MatX>& slice) {
    if (slice.rows() != dofs_ || slice.cols() != frames_) {
        throw InvalidArgument("GramAccumulator::add_slice: the slice must be " + idx(dofs_) + " by " + idx(frames_) +
                              ", got " + idx(slice.rows()) + " by " + idx(slice.cols()));
    }
    add_slices(slice);
}

void GramAccumulator::add_chunk(const Tensor3& chunk) {
    if (chunk.dimension(0) != dofs_ || chunk.dimension(1) != frames_) {
        throw InvalidArgument("GramAccumulator::add_chunk: the chunk must be " + idx(dofs_) + " by " + idx(frames_) +
                              " by k, got " + idx(chunk.dimension(0)) + " by " + idx(chunk.dimension(1)) + " by " +
                              idx(chunk.dimension(2)));
    }
    if (chunk.size() == 0) return;
    add_slices(Eigen::Map<const MatX>(chunk.data(), dofs_, frames_ * chunk.dimension(2)));
}

MatX GramAccumulator::dof_gram() const { return symmetrized(dof_gram_); }

MatX GramAccumulator::time_gram() const { return symmetrized(time_gram_); }

// ---------------------------------------------------------------------------------------------------
MatX mode_gram(const Tensor3& a, int mode) {
    check_tensor(a, "mode_gram");
    if (mode < 0 || mode > 2) {
        throw InvalidArgument("mode_gram: mode must be 0 (dof), 1 (time) or 2 (sample), got " + std::to_string(mode));
    }
    const Eigen::Index d = a.dimension(0), t = a.dimension(1), n = a.dimension(2);
    if (mode == 2) {
        const Eigen::Map<const MatX> m(a.data(), d * t, n);
        MatX g = MatX::Zero(n, n);
        g.selfadjointView<Eigen::Lower>().rankUpdate(m.transpose());
        return symmetrized(g);
    }
    GramAccumulator acc(d, t);
    acc.add_chunk(a);
    return mode == 0 ? acc.dof_gram() : acc.time_gram();
}

namespace {

// Gram matrices from this size on go to LAPACK's divide-and-conquer solver (dsyevd: BLAS-3 work, on
// OpenBLAS's threads; #16: 4.2 s against Eigen's 23-28 s at 3 720); smaller ones stay with Eigen's
// QR iteration, which every dof and time basis has always come from.
constexpr Eigen::Index kLapackEigenMinSize = 512;

// Eigenvectors and ascending eigenvalues of g (lower triangle read) by dsyevd; false (nothing
// computed) below kLapackEigenMinSize, for non-finite input, or if LAPACK does not converge: then
// the caller uses Eigen.
bool lapack_eigen(const Eigen::Ref<const MatX>& g, MatX& vectors, VecX& values) {
    const Eigen::Index n = g.rows();
    if (n < kLapackEigenMinSize || n > static_cast<Eigen::Index>(std::numeric_limits<lapack_int>::max()) ||
        !g.allFinite())
        return false;
    vectors = g;
    values.resize(n);
    const auto size = static_cast<lapack_int>(n);
    const lapack_int info = LAPACKE_dsyevd(LAPACK_COL_MAJOR, 'V', 'L', size, vectors.data(), size, values.data());
    return info == 0 && vectors.allFinite() && values.allFinite();
}

// gram_eigenbasis(g) in g's own storage when dsyevd takes it (the same call on the same matrix, so
// the same values bit for bit; columns reversed and signs fixed in place; #16: no second 0.11 GB
// matrix at 3 720): g becomes the eigenvectors, decreasing. False when gram_eigenbasis would use
// Eigen (g untouched), and when LAPACK fails (g overwritten: `overwritten` is set).
bool eigenbasis_in_place(MatX& g, VecX& out_eigenvalues, bool& overwritten) {
    const Eigen::Index n = g.rows();
    overwritten = false;
    if (n != g.cols() || n < kLapackEigenMinSize ||
        n > static_cast<Eigen::Index>(std::numeric_limits<lapack_int>::max()) || !g.allFinite())
        return false;
    VecX values(n);
    const auto size = static_cast<lapack_int>(n);
    overwritten = true;
    if (LAPACKE_dsyevd(LAPACK_COL_MAJOR, 'V', 'L', size, g.data(), size, values.data()) != 0 || !g.allFinite() ||
        !values.allFinite())
        return false;
    out_eigenvalues.resize(n);
    for (Eigen::Index i = 0; i < n; ++i) out_eigenvalues(i) = std::max(0.0, values(n - 1 - i));
    for (Eigen::Index i = 0; i < n / 2; ++i) g.col(i).swap(g.col(n - 1 - i));
    make_signs_canonical(g);
    return true;
}

}  // namespace

MatX gram_eigenbasis(const Eigen::Ref<const MatX>& g, VecX& out_eigenvalues) {
    if (g.rows() != g.cols() || g.rows() < 1) {
        throw InvalidArgument("gram_eigenbasis: the Gram matrix must be square and non-empty, got " + idx(g.rows()) +
                              " by " + idx(g.cols()));
    }
    const Eigen::Index n = g.rows();
    MatX vectors;  // eigenvectors by ascending eigenvalue
    VecX values;
    if (!lapack_eigen(g, vectors, values)) {
        const Eigen::SelfAdjointEigenSolver<MatX> es(g, Eigen::ComputeEigenvectors);
        vectors = es.eigenvectors();
        values = es.eigenvalues();
    }
    MatX u(n, n);
    out_eigenvalues.resize(n);
    for (Eigen::Index i = 0; i < n; ++i) {
        const Eigen::Index src = n - 1 - i;  // ascending -> decreasing
        out_eigenvalues(i) = std::max(0.0, values(src));
        u.col(i) = vectors.col(src);
        Eigen::Index imax = 0;
        u.col(i).cwiseAbs().maxCoeff(&imax);
        if (u(imax, i) < 0.0) u.col(i) = -u.col(i);
    }
    return u;
}

HosvdBases hosvd_bases_from_grams(const Eigen::Ref<const MatX>& dof_gram, const Eigen::Ref<const MatX>& time_gram,
                                  const Eigen::Ref<const MatX>& sample_gram, double squared_norm) {
    HosvdBases b;
    const Eigen::Ref<const MatX>* grams[3] = {&dof_gram, &time_gram, &sample_gram};
    for (std::size_t n = 0; n < 3; ++n) {
        const Eigen::Ref<const MatX>& g = *grams[n];
        if (g.rows() != g.cols() || g.rows() < 1) {
            throw InvalidArgument(std::string("hosvd_bases_from_grams: the ") + mode_name(static_cast<int>(n)) +
                                  " Gram matrix must be square and non-empty, got " + idx(g.rows()) + " by " +
                                  idx(g.cols()));
        }
        b.U[n] = gram_eigenbasis(g, b.spectra.squared_sv[n]);
        b.spectra.dims[n] = g.rows();
    }
    b.spectra.squared_norm = squared_norm;
    return b;
}

HosvdBases hosvd_bases(const Tensor3& a, const HosvdOptions& options) {
    check_tensor(a, "hosvd");
    if (options.chunk_samples < 1) {
        throw InvalidArgument("hosvd: options.chunk_samples must be >= 1, got " + idx(options.chunk_samples));
    }
    if (!(options.projection_tolerance >= 0.0 && options.projection_tolerance < 1e-6)) {
        throw InvalidArgument("hosvd: options.projection_tolerance must be in [0, 1e-6), got " +
                              std::to_string(options.projection_tolerance));
    }
    const Eigen::Index d = a.dimension(0), t = a.dimension(1), n = a.dimension(2);
    GramAccumulator acc(d, t);
    for (Eigen::Index k0 = 0; k0 < n; k0 += options.chunk_samples) {
        const Eigen::Index k = std::min(options.chunk_samples, n - k0);
        acc.add_slices(Eigen::Map<const MatX>(a.data() + k0 * d * t, d, t * k));
    }
    if (options.sample_basis == SampleBasisMethod::Dense) {
        const MatX g2 = mode_gram(a, 2);
        return hosvd_bases_from_grams(acc.dof_gram(), acc.time_gram(), g2, acc.squared_norm());
    }
    HosvdBases b;
    b.U[0] = gram_eigenbasis(acc.dof_gram(), b.spectra.squared_sv[0]);
    b.U[1] = gram_eigenbasis(acc.time_gram(), b.spectra.squared_sv[1]);
    b.spectra.dims = {d, t, n};
    b.spectra.squared_norm = acc.squared_norm();
    // The dof and time vectors that carry all but the tolerance of the energy (a quarter each; the
    // randomized range of the projected samples may leave out the other half).
    const double budget = 0.25 * options.projection_tolerance * acc.squared_norm();
    const Eigen::Index k0 = kept_for_budget(b.spectra.squared_sv[0], budget);
    const Eigen::Index k1 = kept_for_budget(b.spectra.squared_sv[1], budget);
    if (options.sample_basis == SampleBasisMethod::Auto && n <= k0 * k1) {
        b.U[2] = gram_eigenbasis(mode_gram(a, 2), b.spectra.squared_sv[2]);
        return b;
    }
    MatX coordinates;  // the projected samples' coordinates on U[2]: k0 k1 by K
    bool reduced = false;
    if (k0 == d && k1 == t) {  // nothing to leave out: the samples as stored
        b.U[2] = right_basis_from_row_gram(Eigen::Map<const MatX>(a.data(), d * t, n), 2.0 * budget,
                                           b.spectra.squared_sv[2], nullptr, &coordinates, &reduced);
    } else {
        const auto project = [&](MatX& out) { out = projected_dof_time(a, b.U[0].leftCols(k0), b.U[1].leftCols(k1)); };
        MatX y;
        project(y);
        b.U[2] =
            right_basis_from_row_gram(y, 2.0 * budget, b.spectra.squared_sv[2], &y, &coordinates, &reduced, project);
    }
    b.projected_dofs = k0;
    b.projected_frames = k1;
    b.spans_projected_samples = !reduced;
    // Column j of the coordinates, as a k0 by k1 matrix, is the core's slice j (project_dof_time's
    // order); for the samples as stored it is in the data's own dof and time coordinates: core slice
    // = U0^T (that) U1. Slices by fixed blocks on the machine's cores.
    const Eigen::Index kk = b.U[2].cols();
    b.factored_core = Tensor3(d, t, kk);
    b.factored_core.setZero();
    const bool as_stored = k0 == d && k1 == t;
    for_each_block(kk, [&](Eigen::Index first, Eigen::Index count) {
        MatX dof_side(d, t);
        for (Eigen::Index j = first; j < first + count; ++j) {
            const Eigen::Map<const MatX> c(coordinates.col(j).data(), k0, k1);
            Eigen::Map<MatX> slice(b.factored_core.data() + j * d * t, d, t);
            if (as_stored) {
                dof_side.noalias() = b.U[0].transpose() * c;
                slice.noalias() = dof_side * b.U[1];
            } else {
                slice.topLeftCorner(k0, k1) = c;
            }
        }
    });
    return b;
}

TuckerModel hosvd_from_bases(const Tensor3& a, const HosvdBases& bases, const Ranks& ranks) {
    const Dims3 dims = dims_of(a);
    check_ranks(dims, ranks, "hosvd");
    for (std::size_t n = 0; n < 3; ++n) {
        if (bases.U[n].rows() != dims[n] || (n < 2 && bases.U[n].cols() < ranks[n])) {
            throw InvalidArgument(std::string("hosvd_from_bases: the ") + mode_name(static_cast<int>(n)) +
                                  " basis must have " + idx(dims[n]) + " rows and >= " + idx(ranks[n]) +
                                  " columns, got " + idx(bases.U[n].rows()) + " by " + idx(bases.U[n].cols()));
        }
    }
    TuckerModel m;
    m.method = TuckerMethod::Hosvd;
    m.status = TuckerStatus::Ok;
    m.ranks = ranks;
    m.U[0] = bases.U[0].leftCols(ranks[0]);
    m.U[1] = bases.U[1].leftCols(ranks[1]);
    m.U[2] = sample_basis_columns(bases.U[2], ranks[2]);
    // Project the largest reductions first: the dof mode, then time, then sample (chunk by chunk).
    m.core = projected_core(a, m.U[0], m.U[1], m.U[2]);
    m.data_norm = std::sqrt(bases.spectra.squared_norm);
    m.fit = fit_from(bases.spectra.squared_norm, squared_norm(m.core));
    m.error_bound = hosvd_error_bound(bases.spectra, ranks);
    m.fit_history = {m.fit};
    return m;
}

Tensor3 hosvd_full_core(const Tensor3& a, const HosvdBases& bases) {
    check_tensor(a, "hosvd_full_core");
    const Dims3 dims = dims_of(a);
    for (std::size_t m = 0; m < 3; ++m) {
        if (bases.U[m].rows() != dims[m] || (m < 2 && bases.U[m].cols() != dims[m])) {
            throw InvalidArgument(std::string("hosvd_full_core: the ") + mode_name(static_cast<int>(m)) +
                                  " basis must have " + idx(dims[m]) + " rows" + (m < 2 ? " and columns" : "") +
                                  ", got " + idx(bases.U[m].rows()) + " by " + idx(bases.U[m].cols()));
        }
    }
    return projected_core(a, bases.U[0], bases.U[1], bases.U[2]);
}

namespace {

// hosvd_from_core without the bases' columns (m.U left empty).
TuckerModel core_block_model(const HosvdBases& bases, const Tensor3& full_core, const Ranks& ranks) {
    const Dims3& dims = bases.spectra.dims;
    check_ranks(dims, ranks, "hosvd_from_core");
    for (std::size_t m = 0; m < 3; ++m) {
        if (full_core.dimension(static_cast<int>(m)) < ranks[m] ||
            bases.U[m].cols() != full_core.dimension(static_cast<int>(m))) {
            throw InvalidArgument(std::string("hosvd_from_core: the ") + mode_name(static_cast<int>(m)) + " rank " +
                                  idx(ranks[m]) + " needs a full core of >= " + idx(ranks[m]) +
                                  " matching the basis' " + idx(bases.U[m].cols()) + " columns, got " +
                                  idx(full_core.dimension(static_cast<int>(m))));
        }
    }
    TuckerModel m;
    m.method = TuckerMethod::Hosvd;
    m.status = TuckerStatus::Ok;
    m.ranks = ranks;
    m.core = Tensor3(ranks[0], ranks[1], ranks[2]);
    // Copied slice by slice (#16: a probe's core of 3.7 million values per rank-search probe).
    const Eigen::Index f0 = full_core.dimension(0), f1 = full_core.dimension(1);
    for (Eigen::Index k = 0; k < ranks[2]; ++k)
        Eigen::Map<MatX>(m.core.data() + k * ranks[0] * ranks[1], ranks[0], ranks[1]) =
            Eigen::Map<const MatX>(full_core.data() + k * f0 * f1, f0, f1).topLeftCorner(ranks[0], ranks[1]);
    m.data_norm = std::sqrt(bases.spectra.squared_norm);
    m.fit = fit_from(bases.spectra.squared_norm, squared_norm(m.core));
    m.error_bound = hosvd_error_bound(bases.spectra, ranks);
    m.fit_history = {m.fit};
    return m;
}

}  // namespace

TuckerModel hosvd_from_core(const HosvdBases& bases, const Tensor3& full_core, const Ranks& ranks) {
    TuckerModel m = core_block_model(bases, full_core, ranks);
    for (std::size_t n = 0; n < 3; ++n) m.U[n] = bases.U[n].leftCols(ranks[n]);
    return m;
}

TuckerModel hosvd_from_core(HosvdBases&& bases, const Tensor3& full_core, const Ranks& ranks) {
    TuckerModel m = core_block_model(bases, full_core, ranks);  // full_core is read before bases go
    for (std::size_t n = 0; n < 3; ++n) {
        m.U[n] = std::move(bases.U[n]);
        m.U[n].conservativeResize(Eigen::NoChange, ranks[n]);  // the leading columns stay where they are
    }
    bases = HosvdBases{};
    return m;
}

TuckerModel hosvd(const Tensor3& a, const Ranks& ranks, const HosvdOptions& options) {
    check_tensor(a, "hosvd");
    check_ranks(dims_of(a), ranks, "hosvd");
    const HosvdBases b = hosvd_bases(a, options);
    return hosvd_from_bases(a, b, ranks);
}

TuckerModel st_hosvd(const Tensor3& a, const Ranks& ranks, const std::array<int, 3>& order) {
    check_tensor(a, "st_hosvd");
    check_ranks(dims_of(a), ranks, "st_hosvd");
    std::array<int, 3> sorted = order;
    std::sort(sorted.begin(), sorted.end());
    if (sorted != std::array<int, 3>{0, 1, 2}) {
        throw InvalidArgument("st_hosvd: order must be a permutation of 0, 1, 2, got " + std::to_string(order[0]) +
                              ", " + std::to_string(order[1]) + ", " + std::to_string(order[2]));
    }
    TuckerModel m;
    m.method = TuckerMethod::StHosvd;
    m.status = TuckerStatus::Ok;
    m.ranks = ranks;
    const double norm2 = squared_norm(a);
    double discarded = 0.0;
    Tensor3 b = a;
    for (const int n : order) {
        VecX ev;
        const auto un = static_cast<std::size_t>(n);
        m.U[un] = n == 2 ? sample_mode_basis(b, ranks[un], ev)
                         : MatX(gram_eigenbasis(mode_gram(b, n), ev).leftCols(ranks[un]));
        discarded += ev.tail(ev.size() - ranks[un]).sum();
        b = mode_product_transposed(b, m.U[un], n);
    }
    m.core = std::move(b);
    m.data_norm = std::sqrt(norm2);
    m.fit = fit_from(norm2, squared_norm(m.core));
    m.error_bound = std::sqrt(discarded);
    m.fit_history = {m.fit};
    return m;
}

}  // namespace mocapdb::tensor
