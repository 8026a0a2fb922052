#include "mocapdb/tensor/hosvd.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "hosvd_internal.hpp"
#include "mocapdb/core/error.hpp"
#include "mocapdb/tensor/mode_product.hpp"

namespace mocapdb::tensor {

using detail::fit_from;
using detail::for_each_block;
using detail::idx;
using detail::kept_for_budget;
using detail::projected_core;
using detail::projected_dof_time;
using detail::right_basis_from_row_gram;

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

namespace {

void check_options(const HosvdOptions& options) {
    if (options.chunk_samples < 1) {
        throw InvalidArgument("hosvd: options.chunk_samples must be >= 1, got " + idx(options.chunk_samples));
    }
    if (!(options.projection_tolerance >= 0.0 && options.projection_tolerance < 1e-6)) {
        throw InvalidArgument("hosvd: options.projection_tolerance must be in [0, 1e-6), got " +
                              std::to_string(options.projection_tolerance));
    }
}

/// The dof and time Grams of a, `chunk` samples at a time.
GramAccumulator dof_time_grams(const Tensor3& a, Eigen::Index chunk) {
    const Eigen::Index d = a.dimension(0), t = a.dimension(1), n = a.dimension(2);
    GramAccumulator acc(d, t);
    for (Eigen::Index k0 = 0; k0 < n; k0 += chunk) {
        const Eigen::Index k = std::min(chunk, n - k0);
        acc.add_slices(Eigen::Map<const MatX>(a.data() + k0 * d * t, d, t * k));
    }
    return acc;
}

/// The sample basis (b.U[2]) of the samples projected on the first k0 dof and k1 time vectors (the
/// samples as stored when those are all), and the projected samples' coordinates on it (k0 k1 by
/// its columns). `reduced`: the basis came from a randomized range (right_basis_from_row_gram).
MatX projected_sample_basis(const Tensor3& a, HosvdBases& b, Eigen::Index k0, Eigen::Index k1, double budget,
                            bool& reduced) {
    const Eigen::Index d = a.dimension(0), t = a.dimension(1), n = a.dimension(2);
    MatX coordinates;
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
    return coordinates;
}

/// b.factored_core from the coordinates: column j, as a k0 by k1 matrix, is the core's slice j
/// (project_dof_time's order); for the samples as stored it is in the data's own dof and time
/// coordinates: core slice = U0^T (that) U1. Slices by fixed blocks on the machine's cores.
void fill_factored_core(HosvdBases& b, const MatX& coordinates, Eigen::Index k0, Eigen::Index k1) {
    const Eigen::Index d = b.spectra.dims[0], t = b.spectra.dims[1];
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
}

}  // namespace

HosvdBases hosvd_bases(const Tensor3& a, const HosvdOptions& options) {
    check_tensor(a, "hosvd");
    check_options(options);
    const Eigen::Index d = a.dimension(0), t = a.dimension(1), n = a.dimension(2);
    const GramAccumulator acc = dof_time_grams(a, options.chunk_samples);
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
    bool reduced = false;
    const MatX coordinates = projected_sample_basis(a, b, k0, k1, budget, reduced);
    b.projected_dofs = k0;
    b.projected_frames = k1;
    b.spans_projected_samples = !reduced;
    fill_factored_core(b, coordinates, k0, k1);
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
