#include "mocapdb/tensor/mode_product.hpp"

#include <string>

#include "mocapdb/core/error.hpp"
#include "check_mode.hpp"

namespace mocapdb::tensor {

namespace {

// out = a x_mode op, op: J by I_mode (already checked).
Tensor3 apply(const Tensor3& a, const Eigen::Ref<const MatX>& op, int mode) {
    const Eigen::Index i0 = a.dimension(0), i1 = a.dimension(1), i2 = a.dimension(2);
    const Eigen::Index j = op.rows();
    if (mode == 0) {
        Tensor3 out(j, i1, i2);
        if (out.size() == 0) return out;
        Eigen::Map<MatX> o(out.data(), j, i1 * i2);
        if (i0 == 0) {
            o.setZero();
        } else {
            o.noalias() = op * Eigen::Map<const MatX>(a.data(), i0, i1 * i2);
        }
        return out;
    }
    if (mode == 2) {
        Tensor3 out(i0, i1, j);
        if (out.size() == 0) return out;
        Eigen::Map<MatX> o(out.data(), i0 * i1, j);
        if (i2 == 0) {
            o.setZero();
        } else {
            o.noalias() = Eigen::Map<const MatX>(a.data(), i0 * i1, i2) * op.transpose();
        }
        return out;
    }
    Tensor3 out(i0, j, i2);
    if (out.size() == 0) return out;
    for (Eigen::Index k = 0; k < i2; ++k) {
        Eigen::Map<MatX> o(out.data() + k * i0 * j, i0, j);
        if (i1 == 0) {
            o.setZero();
        } else {
            o.noalias() = Eigen::Map<const MatX>(a.data() + k * i0 * i1, i0, i1) * op.transpose();
        }
    }
    return out;
}

using detail::check_mode;

}  // namespace

Tensor3 mode_product(const Tensor3& a, const Eigen::Ref<const MatX>& m, int mode) {
    check_mode(mode, "mode_product");
    if (m.cols() != a.dimension(mode)) {
        throw InvalidArgument("mode_product: the matrix must have as many columns as the tensor's mode-" +
                              std::to_string(mode) + " dimension (" + std::to_string(a.dimension(mode)) + "), got " +
                              std::to_string(m.rows()) + " by " + std::to_string(m.cols()));
    }
    return apply(a, m, mode);
}

Tensor3 mode_product_transposed(const Tensor3& a, const Eigen::Ref<const MatX>& m, int mode) {
    check_mode(mode, "mode_product_transposed");
    if (m.rows() != a.dimension(mode)) {
        throw InvalidArgument("mode_product_transposed: the matrix must have as many rows as the tensor's mode-" +
                              std::to_string(mode) + " dimension (" + std::to_string(a.dimension(mode)) + "), got " +
                              std::to_string(m.rows()) + " by " + std::to_string(m.cols()));
    }
    const MatX op = m.transpose();
    return apply(a, op, mode);
}

double squared_norm(const Tensor3& a) {
    if (a.size() == 0) return 0.0;
    return Eigen::Map<const VecX>(a.data(), a.size()).squaredNorm();
}

}  // namespace mocapdb::tensor
