// Big synthesis sets (issue #38 item 2): what the subset fit of the coefficient kernel costs in
// accuracy. Loads the set's model as `synth` does (the kernel stored by `compress`: variogram chosen on
// SynthesisOptions::max_fit_samples samples when the set has more), builds a second model whose
// variogram is chosen on all N samples (the exact O(N^3)-per-candidate fit, timed), and compares both
// at Q requests spread uniformly over the samples' parameter box (fixed seed) and at the samples
// themselves: reliability rho (mean and max |difference|) and the synthesized motion's coefficients
// (relative difference |u_sub - u_full| / |u_full|). Prints one `key value` line per figure.
//   bench_synthesis_scale DB.h5 SET [queries=200]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>

#include "bench_timing.hpp"
#include "mocapdb/store/database.hpp"
#include "mocapdb/synthesis/motion_model.hpp"
#include "mocapdb/workflow/aligned_set_data.hpp"
#include "mocapdb/workflow/load_model.hpp"

using namespace mocapdb;
using bench::Clock;
using bench::seconds_since;

int main(int argc, char** argv) {
    if (argc < 3) {
        std::fprintf(stderr, "usage: bench_synthesis_scale DB.h5 SET [queries=200]\n");
        return 2;
    }
    const std::string name = argv[2];
    const int queries = argc > 3 ? std::max(1, std::atoi(argv[3])) : 200;
    const Database db(argv[1]);
    auto t0 = Clock::now();
    const auto sub = workflow::load_motion_model(db, name);
    const double load_s = seconds_since(t0);
    const Eigen::Index n = sub->samples();

    synthesis::SynthesisOptions all;
    all.max_fit_samples = static_cast<std::size_t>(n);
    workflow::AlignedTimingData d = workflow::load_aligned_timing(db, name);
    t0 = Clock::now();
    const synthesis::MotionModel full(db.load_model(name)->model, d.timing, d.set, d.skeleton, d.frame_rate, all);
    const double full_s = seconds_since(t0);

    const MatX& x = sub->sample_parameters();
    std::mt19937 rng(38);
    MatX c(queries + n, x.cols());
    for (Eigen::Index k = 0; k < x.cols(); ++k) {
        std::uniform_real_distribution<double> u(x.col(k).minCoeff(), x.col(k).maxCoeff());
        for (int q = 0; q < queries; ++q) c(q, k) = u(rng);
    }
    c.bottomRows(n) = x;
    const VecX rho_sub = sub->reliability_batch(c), rho_full = full.reliability_batch(c);
    synthesis::Workspace ws;
    VecX us(sub->coefficient_size()), uf(full.coefficient_size());
    double rel_sum = 0.0, rel_max = 0.0;
    for (Eigen::Index q = 0; q < queries; ++q) {
        sub->coefficients(c.row(q).transpose(), us, ws);
        full.coefficients(c.row(q).transpose(), uf, ws);
        const double rel = (us - uf).norm() / std::max(uf.norm(), 1e-300);
        rel_sum += rel;
        rel_max = std::max(rel_max, rel);
    }
    const VecX dq = (rho_sub - rho_full).head(queries).cwiseAbs();
    const VecX ds = (rho_sub - rho_full).tail(n).cwiseAbs();
    std::printf("samples %lld\nqueries %d\n", static_cast<long long>(n), queries);
    std::printf("subset_variogram %s\nfull_variogram %s\n", sub->report().model.to_string().c_str(),
                full.report().model.to_string().c_str());
    std::printf("load_subset_model_s %.3f\nsystem_precomputed %d\nfit_full_model_s %.3f\n", load_s,
                sub->report().system_precomputed ? 1 : 0, full_s);
    std::printf("rho_full_mean %.4f\nrho_abs_diff_mean %.4f\nrho_abs_diff_max %.4f\n", rho_full.head(queries).mean(),
                dq.mean(), dq.maxCoeff());
    std::printf("rho_at_samples_abs_diff_mean %.4f\nrho_at_samples_abs_diff_max %.4f\n", ds.mean(), ds.maxCoeff());
    std::printf("coefficients_rel_diff_mean %.4f\ncoefficients_rel_diff_max %.4f\n", rel_sum / queries, rel_max);
    return 0;
}
