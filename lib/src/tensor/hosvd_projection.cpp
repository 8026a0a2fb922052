// The HOSVD's chunked projections of the samples on the dof and time bases (hosvd_internal.hpp).
#include <array>

#include "hosvd_internal.hpp"

namespace mocapdb::tensor::detail {
namespace {

// Samples [first, first + count) of a projected on the dof and time bases: column i of out (r0 r1
// by count) is u0^T a(:, :, first + i) u1 in column-major order. The same products, in the same
// order, as mode_product_transposed on modes 0 and 1, without a D by T by N intermediate.
void project_dof_time(const Tensor3& a, const Eigen::Ref<const MatX>& u0t, const Eigen::Ref<const MatX>& u1t,
                      Eigen::Index first, Eigen::Index count, Eigen::Ref<MatX> out) {
    const Eigen::Index d = a.dimension(0), t = a.dimension(1), r0 = u0t.rows(), r1 = u1t.rows();
    MatX dof_side(r0, t * count);
    dof_side.noalias() = u0t * Eigen::Map<const MatX>(a.data() + first * d * t, d, t * count);
    for (Eigen::Index i = 0; i < count; ++i) {
        Eigen::Map<MatX> o(out.col(i).data(), r0, r1);
        o.noalias() = dof_side.middleCols(i * t, t) * u1t.transpose();
    }
}

// Samples per chunk of the chunked projections: a few MB of intermediates at D T = 5 400.
constexpr Eigen::Index kProjectionChunk = 128;

}  // namespace

MatX projected_dof_time(const Tensor3& a, const Eigen::Ref<const MatX>& u0, const Eigen::Ref<const MatX>& u1) {
    const Eigen::Index n = a.dimension(2);
    const MatX u0t = u0.transpose(), u1t = u1.transpose();
    MatX y(u0.cols() * u1.cols(), n);
    const auto chunks = static_cast<std::size_t>((n + kProjectionChunk - 1) / kProjectionChunk);
    run_parallel_tasks(chunks, [&](std::size_t c) {
        const Eigen::Index first = static_cast<Eigen::Index>(c) * kProjectionChunk;
        const Eigen::Index count = std::min(kProjectionChunk, n - first);
        project_dof_time(a, u0t, u1t, first, count, y.middleCols(first, count));
    });
    return y;
}

// core = a x_0 u0^T x_1 u1^T x_2 u2^T, chunk by chunk over the samples: core_(2) is the sum over
// chunks of y_chunk u2(chunk, :), y the dof-and-time projection. The chunks are summed in a fixed
// order whatever the number of threads (two halves of the samples, each accumulated in order, then
// added), so the result does not depend on the machine. Memory: two r0 r1 by r2 sums and a chunk each.
Tensor3 projected_core(const Tensor3& a, const Eigen::Ref<const MatX>& u0, const Eigen::Ref<const MatX>& u1,
                       const Eigen::Ref<const MatX>& u2) {
    const Eigen::Index n = a.dimension(2), r0 = u0.cols(), r1 = u1.cols(), r2 = u2.cols();
    const MatX u0t = u0.transpose(), u1t = u1.transpose();
    constexpr std::size_t parts = 2;
    std::array<MatX, parts> partial;
    run_parallel_tasks(parts, [&](std::size_t p) {
        const Eigen::Index begin = n * static_cast<Eigen::Index>(p) / static_cast<Eigen::Index>(parts);
        const Eigen::Index end = n * static_cast<Eigen::Index>(p + 1) / static_cast<Eigen::Index>(parts);
        MatX& acc = partial[p];
        acc = MatX::Zero(r0 * r1, r2);
        MatX y(r0 * r1, std::min(kProjectionChunk, std::max<Eigen::Index>(1, end - begin)));
        for (Eigen::Index first = begin; first < end; first += kProjectionChunk) {
            const Eigen::Index count = std::min(kProjectionChunk, end - first);
            project_dof_time(a, u0t, u1t, first, count, y.leftCols(count));
            acc.noalias() += y.leftCols(count) * u2.middleRows(first, count);
        }
    });
    Tensor3 core(r0, r1, r2);
    Eigen::Map<MatX> c(core.data(), r0 * r1, r2);
    c = partial[0];
    for (std::size_t p = 1; p < parts; ++p) c += partial[p];
    return core;
}

}  // namespace mocapdb::tensor::detail
