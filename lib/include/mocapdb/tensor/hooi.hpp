#pragma once
// Higher-order orthogonal iteration (HOOI, De Lathauwer, De Moor, Vandewalle 2000): alternating
// least-squares refinement of a Tucker model at fixed ranks, started from the truncated HOSVD. Each
// sweep updates U_dof, U_time, U_sample in turn as the leading left singular vectors (via the Gram
// matrix) of A projected on the other two bases; ||G||_F cannot decrease, so the error cannot grow.
#include <Eigen/Core>

#include "mocapdb/tensor/hosvd.hpp"
#include "mocapdb/tensor/tucker.hpp"

namespace mocapdb::tensor {

struct HooiOptions {
    /// Stop when a sweep improves the fit by less than tolerance * fit (relative fit change). >= 0.
    double tolerance = 1e-8;
    /// Maximum number of sweeps (>= 0; 0 returns the HOSVD start).
    int max_iterations = 50;
    /// Passed to the HOSVD start.
    HosvdOptions hosvd;
};

/// HOOI at ranks (R1, R2, R3), started from hosvd(a, ranks).
/// a: D by T by N, non-empty, finite; 1 <= ranks[n] <= dims[n].
/// Returns a model with method Hooi, iterations = sweeps done, fit_history (start + one entry per
/// sweep, non-decreasing), status Converged / MaxIterations / Stalled (a sweep that lowered the fit
/// through rounding ends the iteration; the best model is returned). Never worse than the start.
/// Throws InvalidArgument on bad arguments.
TuckerModel hooi(const Tensor3& a, const Ranks& ranks, const HooiOptions& options = {});

/// HOOI from a given start (any model of a with orthonormal bases, e.g. from hosvd or st_hosvd).
/// a: D by T by N matching start.dims(). Throws InvalidArgument on a shape mismatch or bad options.
TuckerModel hooi(const Tensor3& a, const TuckerModel& start, const HooiOptions& options = {});

}  // namespace mocapdb::tensor
