#include "mocapdb/gp/kernels.hpp"

#include <cmath>

#include "mocapdb/core/error.hpp"

namespace mocapdb::gp {

std::string to_string(KernelType type) {
    switch (type) {
        case KernelType::Rbf: return "rbf";
        case KernelType::Matern32: return "matern32";
    }
    return "unknown";
}

KernelType kernel_type_from_string(const std::string& name) {
    if (name == "rbf" || name == "RBF" || name == "se") return KernelType::Rbf;
    if (name == "matern32" || name == "matern3/2" || name == "Matern32" || name == "matérn32")
        return KernelType::Matern32;
    throw InvalidArgument("unknown kernel '" + name + "' (expected rbf or matern32)");
}

double kernel_value(KernelType type, double log_lengthscale, double r) {
    const double ell = std::exp(log_lengthscale);
    switch (type) {
        case KernelType::Rbf: {
            const double u = r / ell;
            return std::exp(-0.5 * u * u);
        }
        case KernelType::Matern32: {
            const double s = std::sqrt(3.0) * std::abs(r) / ell;
            return (1.0 + s) * std::exp(-s);
        }
    }
    return 0.0;
}

double kernel_dlog_lengthscale(KernelType type, double log_lengthscale, double r) {
    const double ell = std::exp(log_lengthscale);
    switch (type) {
        case KernelType::Rbf: {
            // k = exp(−u²/2), u = r/ℓ, du/dθ = −u  ⇒  dk/dθ = k·u²
            const double u = r / ell;
            return std::exp(-0.5 * u * u) * u * u;
        }
        case KernelType::Matern32: {
            // k = (1+s)e^{−s}, dk/ds = −s e^{−s}, ds/dθ = −s  ⇒  dk/dθ = s² e^{−s}
            const double s = std::sqrt(3.0) * std::abs(r) / ell;
            return s * s * std::exp(-s);
        }
    }
    return 0.0;
}

MatX kernel_matrix(KernelType type, double log_lengthscale, const VecX& t1, const VecX& t2) {
    MatX k(t1.size(), t2.size());
    for (Eigen::Index j = 0; j < t2.size(); ++j)
        for (Eigen::Index i = 0; i < t1.size(); ++i) k(i, j) = kernel_value(type, log_lengthscale, t1[i] - t2[j]);
    return k;
}

MatX kernel_matrix_dlog_lengthscale(KernelType type, double log_lengthscale, const VecX& t1, const VecX& t2) {
    MatX k(t1.size(), t2.size());
    for (Eigen::Index j = 0; j < t2.size(); ++j)
        for (Eigen::Index i = 0; i < t1.size(); ++i)
            k(i, j) = kernel_dlog_lengthscale(type, log_lengthscale, t1[i] - t2[j]);
    return k;
}

}  // namespace mocapdb::gp
