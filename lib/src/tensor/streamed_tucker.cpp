#include "mocapdb/tensor/streamed_tucker.hpp"

#include <cmath>

#include <Eigen/QR>

#include "mocapdb/core/error.hpp"
#include "mocapdb/tensor/hosvd.hpp"

namespace mocapdb::tensor {

TuckerModel streamed_tucker(const SliceSource& source, const Dims3& dims, const Ranks& ranks) {
    check_ranks(dims, ranks, "streamed_tucker");
    const Eigen::Index d = dims[0], t = dims[1], n = dims[2];
    MatX slice(d, t);

    GramAccumulator grams(d, t);
    for (Eigen::Index i = 0; i < n; ++i) {
        source(i, slice);
        grams.add_slice(slice);  // checks finiteness
    }
    VecX dof_ev, time_ev;
    const MatX u_dof = gram_eigenbasis(grams.dof_gram(), dof_ev).leftCols(ranks[0]);
    const MatX u_time = gram_eigenbasis(grams.time_gram(), time_ev).leftCols(ranks[1]);

    const Eigen::Index r12 = ranks[0] * ranks[1];
    MatX m(r12, n);
    for (Eigen::Index i = 0; i < n; ++i) {
        source(i, slice);
        if (!slice.allFinite())
            throw InvalidArgument("streamed_tucker: slice " + std::to_string(i) +
                                  " changed between passes to non-finite values");
        const MatX c = u_dof.transpose() * slice * u_time;
        m.col(i) = Eigen::Map<const VecX>(c.data(), r12);
    }

    // Right singular vectors of M from the smaller Gram matrix.
    MatX u_sample(n, ranks[2]);
    VecX ev;
    double projected_energy = m.squaredNorm();
    if (n <= r12) {
        u_sample = gram_eigenbasis(m.transpose() * m, ev).leftCols(ranks[2]);
    } else {
        const MatX v = gram_eigenbasis(m * m.transpose(), ev);
        const double tiny = 1e-14 * std::max(ev[0], 1e-300);
        Eigen::Index good = 0;
        for (Eigen::Index k = 0; k < ranks[2] && k < ev.size() && ev[k] > tiny; ++k, ++good)
            u_sample.col(k) = m.transpose() * v.col(k) / std::sqrt(ev[k]);
        if (good < ranks[2]) {
            // The projected data has rank < R3: complete the basis orthonormally (the extra columns
            // carry no energy, so any completion is exact).
            MatX seed = MatX::Zero(n, ranks[2]);
            seed.leftCols(good) = u_sample.leftCols(good);
            for (Eigen::Index k = good; k < ranks[2]; ++k) seed(k % n, k) = 1.0;
            Eigen::HouseholderQR<MatX> qr(seed);
            const MatX q = qr.householderQ() * MatX::Identity(n, ranks[2]);
            for (Eigen::Index k = good; k < ranks[2]; ++k) u_sample.col(k) = q.col(k);
        }
    }
    const MatX core = m * u_sample;  // R1 R2 by R3: the core in storage order

    TuckerModel model;
    model.method = TuckerMethod::StHosvd;
    model.status = TuckerStatus::Ok;
    model.ranks = ranks;
    model.U = {u_dof, u_time, u_sample};
    model.core = Tensor3(ranks[0], ranks[1], ranks[2]);
    Eigen::Map<MatX>(model.core.data(), r12, ranks[2]) = core;
    const double norm2 = grams.squared_norm();
    const double core2 = core.squaredNorm();
    model.data_norm = std::sqrt(norm2);
    model.fit = norm2 > 0.0 ? 1.0 - std::sqrt(std::max(0.0, norm2 - core2) / norm2) : 1.0;
    const double discarded =
        dof_ev.tail(d - ranks[0]).sum() + time_ev.tail(t - ranks[1]).sum() + std::max(0.0, projected_energy - core2);
    model.error_bound = std::sqrt(discarded);
    model.fit_history = {model.fit};
    return model;
}

}  // namespace mocapdb::tensor
