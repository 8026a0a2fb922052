#include "mocapdb/tensor/hosvd.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/Eigenvalues>

#include "mocapdb/core/error.hpp"
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

}  // namespace

// ---------------------------------------------------------------------------------------------------
GramAccumulator::GramAccumulator(Eigen::Index dofs, Eigen::Index frames) : dofs_(dofs), frames_(frames) {
    if (dofs < 1 || frames < 1) {
        throw InvalidArgument("GramAccumulator: dofs and frames must be >= 1, got " + idx(dofs) + " and " + idx(frames));
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

MatX gram_eigenbasis(const Eigen::Ref<const MatX>& g, VecX& out_eigenvalues) {
    if (g.rows() != g.cols() || g.rows() < 1) {
        throw InvalidArgument("gram_eigenbasis: the Gram matrix must be square and non-empty, got " + idx(g.rows()) +
                              " by " + idx(g.cols()));
    }
    const Eigen::SelfAdjointEigenSolver<MatX> es(g, Eigen::ComputeEigenvectors);
    const Eigen::Index n = g.rows();
    MatX u(n, n);
    out_eigenvalues.resize(n);
    for (Eigen::Index i = 0; i < n; ++i) {
        const Eigen::Index src = n - 1 - i;  // ascending -> decreasing
        out_eigenvalues(i) = std::max(0.0, es.eigenvalues()(src));
        u.col(i) = es.eigenvectors().col(src);
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
    const Eigen::Index d = a.dimension(0), t = a.dimension(1), n = a.dimension(2);
    GramAccumulator acc(d, t);
    for (Eigen::Index k0 = 0; k0 < n; k0 += options.chunk_samples) {
        const Eigen::Index k = std::min(options.chunk_samples, n - k0);
        acc.add_slices(Eigen::Map<const MatX>(a.data() + k0 * d * t, d, t * k));
    }
    const MatX g2 = mode_gram(a, 2);
    return hosvd_bases_from_grams(acc.dof_gram(), acc.time_gram(), g2, acc.squared_norm());
}

TuckerModel hosvd_from_bases(const Tensor3& a, const HosvdBases& bases, const Ranks& ranks) {
    const Dims3 dims = dims_of(a);
    check_ranks(dims, ranks, "hosvd");
    for (std::size_t n = 0; n < 3; ++n) {
        if (bases.U[n].rows() != dims[n] || bases.U[n].cols() < ranks[n]) {
            throw InvalidArgument(std::string("hosvd_from_bases: the ") + mode_name(static_cast<int>(n)) +
                                  " basis must have " + idx(dims[n]) + " rows and >= " + idx(ranks[n]) +
                                  " columns, got " + idx(bases.U[n].rows()) + " by " + idx(bases.U[n].cols()));
        }
    }
    TuckerModel m;
    m.method = TuckerMethod::Hosvd;
    m.status = TuckerStatus::Ok;
    m.ranks = ranks;
    for (std::size_t n = 0; n < 3; ++n) m.U[n] = bases.U[n].leftCols(ranks[n]);
    // Project the largest reductions first: the dof mode, then time, then sample.
    Tensor3 c = mode_product_transposed(a, m.U[0], 0);
    c = mode_product_transposed(c, m.U[1], 1);
    m.core = mode_product_transposed(c, m.U[2], 2);
    m.data_norm = std::sqrt(bases.spectra.squared_norm);
    m.fit = fit_from(bases.spectra.squared_norm, squared_norm(m.core));
    m.error_bound = hosvd_error_bound(bases.spectra, ranks);
    m.fit_history = {m.fit};
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
        const MatX u = gram_eigenbasis(mode_gram(b, n), ev);
        const auto un = static_cast<std::size_t>(n);
        m.U[un] = u.leftCols(ranks[un]);
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
