#include "mocapdb/tensor/hooi.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "hosvd_internal.hpp"
#include "mocapdb/core/error.hpp"
#include "mocapdb/tensor/mode_product.hpp"

namespace mocapdb::tensor {

using detail::fit_from;
using detail::idx;

namespace {

// Leading r left singular vectors of y_(mode), from its Gram matrix.
MatX leading_basis(const Tensor3& y, int mode, Eigen::Index r) {
    VecX ev;
    if (mode == 2) return sample_mode_basis(y, r, ev);  // no N by N Gram when N is the larger side
    const MatX u = gram_eigenbasis(mode_gram(y, mode), ev);
    return u.leftCols(r);
}

}  // namespace

TuckerModel hooi(const Tensor3& a, const TuckerModel& start, const HooiOptions& options) {
    check_tensor(a, "hooi");
    const Dims3 dims = dims_of(a);
    if (start.dims() != dims) {
        throw InvalidArgument("hooi: the start model is " + idx(start.dims()[0]) + " by " + idx(start.dims()[1]) +
                              " by " + idx(start.dims()[2]) + " but the tensor is " + idx(dims[0]) + " by " +
                              idx(dims[1]) + " by " + idx(dims[2]));
    }
    check_ranks(dims, start.ranks, "hooi");
    if (!(options.tolerance >= 0.0) || !std::isfinite(options.tolerance)) {
        throw InvalidArgument("hooi: options.tolerance must be finite and >= 0, got " +
                              std::to_string(options.tolerance));
    }
    if (options.max_iterations < 0) {
        throw InvalidArgument("hooi: options.max_iterations must be >= 0, got " +
                              std::to_string(options.max_iterations));
    }
    const Ranks& r = start.ranks;
    const double norm2 = squared_norm(a);

    TuckerModel best = start;
    best.method = TuckerMethod::Hooi;
    best.iterations = 0;
    best.data_norm = std::sqrt(norm2);
    double best_core2 = squared_norm(start.core);
    best.fit = fit_from(norm2, best_core2);
    best.fit_history = {best.fit};
    best.status = TuckerStatus::MaxIterations;
    if (options.max_iterations == 0) return best;

    std::array<MatX, 3> u = start.U;
    for (int it = 1; it <= options.max_iterations; ++it) {
        // Dof basis: A x_1 U_time^T x_2 U_sample^T, D by R2 by R3 (the sample projection first: largest cut).
        {
            const Tensor3 y = mode_product_transposed(mode_product_transposed(a, u[2], 2), u[1], 1);
            u[0] = leading_basis(y, 0, r[0]);
        }
        // Time and sample bases share A x_0 U_dof^T (R1 by T by N).
        const Tensor3 z = mode_product_transposed(a, u[0], 0);
        u[1] = leading_basis(mode_product_transposed(z, u[2], 2), 1, r[1]);
        const Tensor3 y2 = mode_product_transposed(z, u[1], 1);  // R1 by R2 by N
        u[2] = leading_basis(y2, 2, r[2]);
        Tensor3 core = mode_product_transposed(y2, u[2], 2);
        const double core2 = squared_norm(core);
        if (core2 < best_core2) {  // only rounding can do this: keep the best model and stop
            best.status = TuckerStatus::Stalled;
            return best;
        }
        const double previous_fit = best.fit;
        best.core = std::move(core);
        best.U = u;
        best_core2 = core2;
        best.fit = fit_from(norm2, core2);
        best.fit_history.push_back(best.fit);
        best.iterations = it;
        if (best.fit - previous_fit <= options.tolerance * std::abs(best.fit)) {
            best.status = TuckerStatus::Converged;
            return best;
        }
    }
    best.status = TuckerStatus::MaxIterations;
    return best;
}

TuckerModel hooi(const Tensor3& a, const Ranks& ranks, const HooiOptions& options) {
    return hooi(a, hosvd(a, ranks, options.hosvd), options);
}

}  // namespace mocapdb::tensor
