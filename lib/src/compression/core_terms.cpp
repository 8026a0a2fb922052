#include "core_terms.hpp"

#include <algorithm>

#include "mocapdb/core/parallel_tasks.hpp"

namespace mocapdb::compression::detail {

void core_terms(const Tensor3& core, const Eigen::Ref<const MatX>& dof_basis, const Eigen::Ref<const MatX>& time_basis,
                Eigen::Index first, Eigen::Index last, MatX& out) {
    const Eigen::Index d = dof_basis.rows(), t = time_basis.rows();
    const Eigen::Index r0 = dof_basis.cols(), r1 = time_basis.cols();
    const Eigen::Index f0 = core.dimension(0), f1 = core.dimension(1);
    out.resize(d * t, last - first);
    constexpr Eigen::Index kSlices = 64;
    run_parallel_tasks(static_cast<std::size_t>((last - first + kSlices - 1) / kSlices), [&](std::size_t c) {
        const Eigen::Index begin = first + static_cast<Eigen::Index>(c) * kSlices;
        MatX w0(d, r1);
        for (Eigen::Index j = begin; j < std::min(last, begin + kSlices); ++j) {
            w0.noalias() = dof_basis * Eigen::Map<const MatX>(core.data() + j * f0 * f1, f0, f1).topLeftCorner(r0, r1);
            Eigen::Map<MatX> o(out.col(j - first).data(), d, t);
            o.noalias() = w0 * time_basis.transpose();
        }
    });
}

}  // namespace mocapdb::compression::detail
