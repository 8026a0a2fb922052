#pragma once
// Internal to the gp module: the output-major vectorization, in-place Cholesky helpers and the small
// task runner shared by the likelihood and posterior code.
#include <functional>
#include <vector>

#include "mocapdb/core/types.hpp"

namespace mocapdb::gp::detail {

constexpr double kLog2Pi = 1.8378770664093454836;

/// Output-major vector of a D by T matrix: y[d·T + t] = Y(d, t).
VecX vec_output_major(const MatX& y);
MatX unvec_output_major(const VecX& v, Eigen::Index d, Eigen::Index t);
/// The D noise variances repeated over T frames, output-major.
VecX flat_noise(const VecX& noise, Eigen::Index t);

/// In-place Cholesky of the SPD matrix m (lower triangle); false when not positive definite.
bool factor_in_place(MatX& m, double& out_log_det);
/// Replaces the Cholesky factor L held in m's lower triangle by the full symmetric inverse (L Lᵀ)⁻¹.
void invert_from_factor_in_place(MatX& m);

/// Runs independent tasks, on two threads when `threads` ≥ 2 and there are several tasks; a task's
/// exception is rethrown here (the first task's that threw), never lost on a worker thread.
void run_tasks(const std::vector<std::function<void()>>& tasks, int threads);

}  // namespace mocapdb::gp::detail
