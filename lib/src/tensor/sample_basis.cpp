// The sample-mode basis of the HOSVD (hosvd_internal.hpp, mocapdb/tensor/hosvd.hpp): right singular
// vectors of the samples from their row Gram, on a randomized range when the energy allows.
#include <cmath>
#include <random>
#include <vector>

#include <Eigen/QR>

#include "hosvd_internal.hpp"
#include "mocapdb/core/error.hpp"
#include "mocapdb/tensor/hosvd.hpp"

namespace mocapdb::tensor {
namespace detail {
namespace {

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

}  // namespace

MatX right_basis_from_row_gram(const Eigen::Ref<const MatX>& m, double budget, VecX& out_eigenvalues, MatX* owner,
                               MatX* out_coordinates, bool* out_reduced,
                               const std::function<void(MatX&)>& rebuild_owner) {
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

Eigen::Index kept_for_budget(const VecX& ev, double budget) {
    Eigen::Index k = ev.size();
    double tail = 0.0;
    while (k > 1 && tail + ev(k - 1) <= budget) tail += ev(--k);
    return k;
}

}  // namespace detail

using detail::idx;
using detail::kKeptEnergy;
using detail::right_basis_from_row_gram;

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

}  // namespace mocapdb::tensor
