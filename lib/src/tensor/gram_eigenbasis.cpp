// Gram matrices of a tensor's unfoldings and their eigenbases (mocapdb/tensor/hosvd.hpp): Eigen's QR
// iteration for small Grams, LAPACK's dsyevd for large ones; eigenbasis_in_place (hosvd_internal.hpp).
#include <limits>

#include <Eigen/Eigenvalues>
#include <lapacke.h>

#include "hosvd_internal.hpp"
#include "mocapdb/core/error.hpp"
#include "mocapdb/tensor/hosvd.hpp"

namespace mocapdb::tensor {

using detail::idx;
using detail::symmetrized;

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

}  // namespace

namespace detail {

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

}  // namespace detail

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

}  // namespace mocapdb::tensor
