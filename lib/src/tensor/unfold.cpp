#include "mocapdb/tensor/unfold.hpp"

#include <string>

#include "mocapdb/core/error.hpp"
#include "check_mode.hpp"

namespace mocapdb::tensor {

namespace {

using detail::check_mode;

}  // namespace

Dims3 dims_of(const Tensor3& a) { return {a.dimension(0), a.dimension(1), a.dimension(2)}; }

const char* mode_name(int mode) {
    switch (mode) {
        case 0: return "dof";
        case 1: return "time";
        case 2: return "sample";
        default: return "invalid";
    }
}

MatX unfold(const Tensor3& a, int mode) {
    check_mode(mode, "unfold");
    const Eigen::Index i0 = a.dimension(0), i1 = a.dimension(1), i2 = a.dimension(2);
    if (mode == 0) return Eigen::Map<const MatX>(a.data(), i0, i1 * i2);
    if (mode == 2) return Eigen::Map<const MatX>(a.data(), i0 * i1, i2).transpose();
    MatX out(i1, i0 * i2);
    for (Eigen::Index k = 0; k < i2; ++k) {
        const Eigen::Map<const MatX> slice(a.data() + k * i0 * i1, i0, i1);
        out.middleCols(k * i0, i0) = slice.transpose();
    }
    return out;
}

Tensor3 fold(const Eigen::Ref<const MatX>& m, int mode, const Dims3& dims) {
    check_mode(mode, "fold");
    for (int n = 0; n < 3; ++n) {
        if (dims[n] < 0)
            throw InvalidArgument("fold: dims must be >= 0, got " + std::to_string(dims[n]) + " for mode " +
                                  std::to_string(n));
    }
    const Eigen::Index i0 = dims[0], i1 = dims[1], i2 = dims[2];
    const Eigen::Index rows = dims[mode];
    const Eigen::Index expected_cols = mode == 0 ? i1 * i2 : mode == 1 ? i0 * i2 : i0 * i1;
    if (m.rows() != rows || m.cols() != expected_cols) {
        throw InvalidArgument("fold: the mode-" + std::to_string(mode) + " unfolding of a " + std::to_string(i0) +
                              " by " + std::to_string(i1) + " by " + std::to_string(i2) + " tensor must be " +
                              std::to_string(rows) + " by " + std::to_string(expected_cols) + ", got " +
                              std::to_string(m.rows()) + " by " + std::to_string(m.cols()));
    }
    Tensor3 out(i0, i1, i2);
    if (out.size() == 0) return out;
    if (mode == 0) {
        Eigen::Map<MatX>(out.data(), i0, i1 * i2) = m;
    } else if (mode == 2) {
        Eigen::Map<MatX>(out.data(), i0 * i1, i2) = m.transpose();
    } else {
        for (Eigen::Index k = 0; k < i2; ++k) {
            Eigen::Map<MatX>(out.data() + k * i0 * i1, i0, i1) = m.middleCols(k * i0, i0).transpose();
        }
    }
    return out;
}

}  // namespace mocapdb::tensor
