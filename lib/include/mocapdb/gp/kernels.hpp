#pragma once
// Stationary base kernels on scalar inputs (time, seconds) for the multi-output GPs of this module.
// Each has unit variance (the scale lives in the coregionalization matrices) and one hyperparameter,
// the lengthscale ℓ, parametrized by its logarithm θ = log ℓ so that any real θ is valid.
#include <string>

#include "mocapdb/core/types.hpp"

namespace mocapdb::gp {

enum class KernelType {
    Rbf,       ///< k(r) = exp(−r² / (2ℓ²))
    Matern32,  ///< k(r) = (1 + √3 r/ℓ) exp(−√3 r/ℓ)
};

/// "rbf" or "matern32".
std::string to_string(KernelType type);
/// Parses "rbf" / "matern32" (also "matern3/2", "matérn32"); InvalidArgument otherwise.
KernelType kernel_type_from_string(const std::string& name);

/// k(t, t') for r = |t − t'|, lengthscale exp(log_lengthscale).
double kernel_value(KernelType type, double log_lengthscale, double r);
/// ∂k/∂θ (θ = log ℓ) at distance r.
double kernel_dlog_lengthscale(KernelType type, double log_lengthscale, double r);

/// Kernel matrix: t1.size() by t2.size(), entry (i, j) = k(t1[i], t2[j]).
MatX kernel_matrix(KernelType type, double log_lengthscale, const VecX& t1, const VecX& t2);
/// Entry-wise ∂/∂θ of kernel_matrix.
MatX kernel_matrix_dlog_lengthscale(KernelType type, double log_lengthscale, const VecX& t1, const VecX& t2);

}  // namespace mocapdb::gp
