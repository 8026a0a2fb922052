// pack_group's pass 0 (pack_stages.hpp): the group's bases, their energies and the scan.
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "pack_stages.hpp"

namespace mocapdb::packing::detail {
namespace {

/// Second moments of the weighted active dofs along dofs (Da by Da) and along time (W by W), lower
/// triangles, summed over windows.
struct Moments {
    MatX dof, time;
    std::uint64_t windows = 0;
};

/// The group's moments: per clip, summed in clip order afterwards (the bases, and so the bytes, do
/// not depend on how clips were spread over threads).
Moments group_moments(PackRun& run, const GroupModel& m) {
    const auto D = static_cast<Eigen::Index>(m.active.size());
    const int W = m.window;
    std::vector<Moments> per_clip(run.clips.size());
    std::vector<int> no_state(run.threads);
    run.run(
        [&](std::size_t i, int&) {
            const ClipEntry& e = m.clips[i];
            const MatX x = m.weighted_active(*run.clips[i], m.skeletons[e.skeleton], e.canonical);
            const auto nw = static_cast<int>(window_count(e.frames, W));
            Moments mo{MatX::Zero(D, D), MatX::Zero(W, W), 0};
            for (int w = 0; w < nw; ++w) {
                ++mo.windows;
                if (D == 0)
                    continue;  // every dof constant: no moments (and Eigen's rankUpdate of an empty matrix is UB)
                const MatX xw = window_of(x, w, W);
                mo.dof.selfadjointView<Eigen::Lower>().rankUpdate(xw);
                mo.time.selfadjointView<Eigen::Lower>().rankUpdate(xw.transpose());
            }
            per_clip[i] = std::move(mo);
            run.done(*run.clips[i], nw);
        },
        no_state);
    Moments sum{MatX::Zero(D, D), MatX::Zero(W, W), 0};
    for (Moments& mo : per_clip) {
        sum.dof += mo.dof;
        sum.time += mo.time;
        sum.windows += mo.windows;
        mo = Moments{};
    }
    return sum;
}

/// Descending eigen-decomposition of a symmetric matrix; basis rounded to multiples of kBasisStep
/// (as stored).
void eigen_basis(const MatX& moment, MatX& out_basis, std::vector<double>& out_values) {
    const auto n = moment.rows();
    out_basis.resize(n, n);
    out_values.resize(static_cast<std::size_t>(n));
    if (n == 0) return;  // every dof constant
    Eigen::SelfAdjointEigenSolver<MatX> solver(moment);
    for (Eigen::Index i = 0; i < n; ++i) {
        out_basis.col(i) = (solver.eigenvectors().col(n - 1 - i) / kBasisStep).array().round() * kBasisStep;
        out_values[static_cast<std::size_t>(i)] = std::max(0.0, solver.eigenvalues()[n - 1 - i]);
    }
}

/// Orthonormal DCT-II as the time basis, rounded like a learned basis; energies as the learned ones'.
void cosine_time_basis(const MatX& time_moment, MatX& basis, std::vector<double>& values) {
    const auto W = static_cast<int>(basis.cols());
    for (int k = 0; k < W; ++k) {
        const double scale = std::sqrt((k == 0 ? 1.0 : 2.0) / W);
        for (int t = 0; t < W; ++t)
            basis(t, k) = std::round(scale * std::cos(kPi * (t + 0.5) * k / W) / kBasisStep) * kBasisStep;
        values[static_cast<std::size_t>(k)] = std::max(0.0, basis.col(k).dot(time_moment * basis.col(k)));
    }
}

}  // namespace

void fit_bases(PackRun& run, GroupModel& m) {
    const Moments sum = group_moments(run, m);
    const MatX dof_moment = sum.dof.selfadjointView<Eigen::Lower>();
    const MatX time_moment = sum.time.selfadjointView<Eigen::Lower>();
    std::vector<double> dof_values, time_values;
    eigen_basis(dof_moment, m.dof_basis, dof_values);
    eigen_basis(time_moment, m.time_basis, time_values);
    if (run.options.time_basis == TimeBasis::Cosine) cosine_time_basis(time_moment, m.time_basis, time_values);
    if (run.options.dof_basis == DofBasis::Identity) {
        m.dof_basis.setIdentity();
        for (Eigen::Index d = 0; d < dof_moment.rows(); ++d)
            dof_values[static_cast<std::size_t>(d)] = std::max(0.0, dof_moment(d, d));
    }
    double total = 0.0;
    for (double v : dof_values) total += v;
    const double nw = static_cast<double>(std::max<std::uint64_t>(1, sum.windows));
    for (double v : dof_values) m.dof_energy.push_back(static_cast<float>(v / nw));
    for (double v : time_values) m.time_energy.push_back(static_cast<float>(total > 0 ? v / total : 0.0));
    m.build_scan();
}

}  // namespace mocapdb::packing::detail
