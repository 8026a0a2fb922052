#include "gp_internal.hpp"

#include <cmath>

#include <Eigen/Cholesky>

#include "mocapdb/core/parallel_tasks.hpp"

namespace mocapdb::gp::detail {

VecX vec_output_major(const MatX& y) {
    VecX v(y.size());
    const Eigen::Index t = y.cols();
    for (Eigen::Index d = 0; d < y.rows(); ++d) v.segment(d * t, t) = y.row(d).transpose();
    return v;
}

MatX unvec_output_major(const VecX& v, Eigen::Index d, Eigen::Index t) {
    MatX y(d, t);
    for (Eigen::Index i = 0; i < d; ++i) y.row(i) = v.segment(i * t, t).transpose();
    return y;
}

VecX flat_noise(const VecX& noise, Eigen::Index t) {
    VecX v(noise.size() * t);
    for (Eigen::Index d = 0; d < noise.size(); ++d) v.segment(d * t, t).setConstant(noise[d]);
    return v;
}

bool factor_in_place(MatX& m, double& out_log_det) {
    Eigen::LLT<Eigen::Ref<MatX>> llt(m);
    if (llt.info() != Eigen::Success) return false;
    const auto diag = m.diagonal();
    for (Eigen::Index i = 0; i < diag.size(); ++i)
        if (!(diag[i] > 0.0) || !std::isfinite(diag[i])) return false;
    out_log_det = 2.0 * diag.array().log().sum();
    return std::isfinite(out_log_det);
}

// Blocked: X = L⁻¹ column block by column block (each a triangular solve restricted to the rows at and
// below the block, ≈ n³/3 flops), written over L; then (L Lᵀ)⁻¹ = Xᵀ X one column block of its upper
// triangle at a time (≈ n³/3 flops), also in place; finally the lower triangle is mirrored.
void invert_from_factor_in_place(MatX& m) {
    const Eigen::Index n = m.rows();
    const Eigen::Index bs = 96;
    MatX rhs;
    for (Eigen::Index j0 = 0; j0 < n; j0 += bs) {
        const Eigen::Index bb = std::min(bs, n - j0);
        const Eigen::Index rows = n - j0;
        rhs.setZero(rows, bb);
        rhs.topRows(bb).setIdentity();
        m.block(j0, j0, rows, rows).triangularView<Eigen::Lower>().solveInPlace(rhs);
        m.block(j0, j0, rows, bb) = rhs;  // upper part of the diagonal block becomes 0 (exact)
    }
    // Now the lower triangle (with diagonal) of m holds X = L⁻¹ (the strict upper parts of the diagonal
    // blocks are exact zeros; the rest of the upper triangle is stale). Inverse = Xᵀ X, its upper
    // triangle one column block J = [j0, j1) at a time: Inv(0:j1, J) = X(j0:n, 0:j1)ᵀ X(j0:n, J).
    // Block J only reads rows ≥ j0 and writes rows < j1 of column block J; later blocks read rows ≥ j1
    // only, so the update is safe in place in increasing J.
    MatX tmp;
    for (Eigen::Index j0 = 0; j0 < n; j0 += bs) {
        const Eigen::Index bb = std::min(bs, n - j0);
        const Eigen::Index j1 = j0 + bb;
        const Eigen::Index rows = n - j0;
        tmp.noalias() = m.block(j0, 0, rows, j1).transpose() * m.block(j0, j0, rows, bb).triangularView<Eigen::Lower>();
        m.block(0, j0, j1, bb) = tmp;
    }
    for (Eigen::Index j = 0; j < n; ++j)
        for (Eigen::Index i = j + 1; i < n; ++i) m(i, j) = m(j, i);
}

void run_tasks(const std::vector<std::function<void()>>& tasks, int threads) {
    // Two workers take the next task in order: a lone task at the end runs on whichever is free. A
    // task's exception reaches the caller (run_on_workers).
    run_on_workers(threads < 2 ? 1 : 2, tasks.size(), [&tasks](std::size_t i, std::size_t) { tasks[i](); });
}

}  // namespace mocapdb::gp::detail
