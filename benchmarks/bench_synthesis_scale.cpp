// Big synthesis sets (issue #38 item 2): what the approximations for big sets cost in accuracy.
//
// Mode `subset` (default): the subset fit of the coefficient kernel. Loads the set's model as `synth`
// does (the kernel stored by `compress`: variogram chosen on SynthesisOptions::max_fit_samples samples
// when the set has more), builds a second model whose variogram is chosen on all N samples (the exact
// O(N^3)-per-candidate fit, timed), and compares both at Q requests spread uniformly over the samples'
// parameter box (fixed seed) and at the samples themselves: reliability rho (mean and max |difference|)
// and the synthesized motion's coefficients (relative difference |u_sub - u_full| / |u_full|).
//
// Mode `local`: local kriging (k nearest samples, SynthesisOptions::local_neighbours) against the exact
// kriging of all samples, both with the stored variogram: load and one synth timed for each; at the Q
// requests the coefficients (relative difference), the poses (joint positions, cm, every aligned frame)
// and rho; and at held-out samples (every `holdout`-th, the kriging systems built on the others) the
// same differences plus each predictor's error against the held-out sample itself. A set above
// max_exact_samples loads local by default: then only the local figures (no exact system is built).
// Prints one `key value` line per figure.
//   bench_synthesis_scale DB.h5 SET [queries=200] [subset | local [k=300] [holdout=20]]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "bench_timing.hpp"
#include "mocapdb/compression/joint_error.hpp"
#include "mocapdb/kriging/local_kriging.hpp"
#include "mocapdb/store/database.hpp"
#include "mocapdb/synthesis/motion_model.hpp"
#include "mocapdb/workflow/aligned_set_data.hpp"
#include "mocapdb/workflow/load_model.hpp"

using namespace mocapdb;
using bench::Clock;
using bench::seconds_since;

namespace {

// Uniform requests over the samples' parameter box (fixed seed): Q by P.
MatX box_requests(const MatX& x, int queries) {
    std::mt19937 rng(38);
    MatX c(queries, x.cols());
    for (Eigen::Index k = 0; k < x.cols(); ++k) {
        std::uniform_real_distribution<double> u(x.col(k).minCoeff(), x.col(k).maxCoeff());
        for (int q = 0; q < queries; ++q) c(q, k) = u(rng);
    }
    return c;
}

// The first three fields of /proc/loadavg ("?" when unreadable).
std::string load_average() {
    std::FILE* f = std::fopen("/proc/loadavg", "r");
    if (!f) return "?";
    double a = 0.0, b = 0.0, c = 0.0;
    const int got = std::fscanf(f, "%lf %lf %lf", &a, &b, &c);
    std::fclose(f);
    if (got != 3) return "?";
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.2f %.2f %.2f", a, b, c);
    return buf;
}

int subset_mode(const Database& db, const std::string& name, int queries) {
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
    MatX c(queries + n, x.cols());
    c.topRows(queries) = box_requests(x, queries);
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

// Joint positions (cm) of the motion with coefficients u at every aligned frame: 3J by T.
MatX positions(const synthesis::MotionModel& m, const VecX& u) {
    MatX poses(m.dofs(), m.frames());
    synthesis::Workspace ws;
    for (Eigen::Index t = 0; t < m.frames(); ++t)
        m.pose_from_coefficients(u, static_cast<double>(t), poses.col(t), ws);
    return compression::pose_joint_positions(*m.skeleton(), poses);
}

// Mean and max over joints and frames of the distance between two position sets (3J by T).
struct Gap {
    double mean = 0.0, max = 0.0;
};
Gap gap(const MatX& a, const MatX& b) {
    Gap g;
    Eigen::Index count = 0;
    for (Eigen::Index t = 0; t < a.cols(); ++t)
        for (Eigen::Index j = 0; j + 2 < a.rows(); j += 3) {
            const double d = (a.block(j, t, 3, 1) - b.block(j, t, 3, 1)).norm();
            g.mean += d;
            g.max = std::max(g.max, d);
            ++count;
        }
    g.mean /= static_cast<double>(std::max<Eigen::Index>(count, 1));
    return g;
}

// Running mean of the means and max of the maxima of several gaps.
struct Gaps {
    double sum = 0.0, max = 0.0;
    int n = 0;
    void add(const Gap& g) {
        sum += g.mean;
        max = std::max(max, g.max);
        ++n;
    }
    void print(const char* key) const {
        std::printf("%s_cm_mean %.4f\n%s_cm_max %.4f\n", key, sum / std::max(n, 1), key, max);
    }
};

int local_mode(const Database& db, const std::string& name, int queries, int k, int holdout) {
    std::printf("load_average %s\n", load_average().c_str());
    auto t0 = Clock::now();
    const auto by_default = workflow::load_motion_model(db, name);
    const double load_default_s = seconds_since(t0);
    const Eigen::Index n = by_default->samples();
    std::printf("samples %lld\nneighbours %d\nvariogram %s\n", static_cast<long long>(n), k,
                by_default->report().model.to_string().c_str());
    synthesis::SynthesisOptions lo;
    lo.max_exact_samples = 1;  // every set local
    lo.local_neighbours = static_cast<std::size_t>(k);
    t0 = Clock::now();
    const auto local = workflow::load_motion_model(db, name, lo);
    const double load_local_s = seconds_since(t0);
    const MatX c = box_requests(local->sample_parameters(), queries);
    const VecX c0 = c.row(0).transpose();
    t0 = Clock::now();
    const Eigen::Index frames_local = local->motion_poses(c0).cols();
    const double synth_local_s = seconds_since(t0);
    std::printf("load_local_s %.3f\nsynth_local_s %.4f\nsynth_local_frames %lld\n", load_local_s, synth_local_s,
                static_cast<long long>(frames_local));
    synthesis::Workspace ws;
    VecX ul(local->coefficient_size()), ue(local->coefficient_size());
    t0 = Clock::now();
    for (Eigen::Index q = 0; q < c.rows(); ++q) local->coefficients(c.row(q).transpose(), ul, ws);
    std::printf("local_query_ms %.3f\n", 1e3 * seconds_since(t0) / static_cast<double>(c.rows()));
    if (by_default->local_kernel()) {
        std::printf("default_load_is_local 1\nload_default_s %.3f\n", load_default_s);
        return 0;
    }
    const synthesis::MotionModel& exact = *by_default;
    t0 = Clock::now();
    const Eigen::Index frames_exact = exact.motion_poses(c0).cols();
    const double synth_exact_s = seconds_since(t0);
    std::printf("load_exact_s %.3f\nsystem_precomputed %d\nsynth_exact_s %.4f\nsynth_exact_frames %lld\n",
                load_default_s, exact.report().system_precomputed ? 1 : 0, synth_exact_s,
                static_cast<long long>(frames_exact));

    // At the requests: the two models (also split at the exact rho 0.5: near the samples / far from them).
    const VecX rho_exact = exact.reliability_batch(c);
    double rel_sum = 0.0, rel_max = 0.0;
    Gaps at_requests, near, far;
    for (Eigen::Index q = 0; q < c.rows(); ++q) {
        exact.coefficients(c.row(q).transpose(), ue, ws);
        local->coefficients(c.row(q).transpose(), ul, ws);
        const double rel = (ul - ue).norm() / std::max(ue.norm(), 1e-300);
        rel_sum += rel;
        rel_max = std::max(rel_max, rel);
        const Gap g = gap(positions(exact, ue), positions(exact, ul));
        at_requests.add(g);
        (rho_exact(q) >= 0.5 ? near : far).add(g);
    }
    const VecX drho = (local->reliability_batch(c) - rho_exact).cwiseAbs();
    std::printf("queries %d\nrequests_rho_exact_mean %.4f\n", queries, rho_exact.mean());
    std::printf("requests_coefficients_rel_diff_mean %.5f\nrequests_coefficients_rel_diff_max %.5f\n",
                rel_sum / queries, rel_max);
    at_requests.print("requests_pose_diff");
    std::printf("requests_rho_at_least_half %d\n", near.n);
    near.print("requests_rho_at_least_half_pose_diff");
    far.print("requests_rho_below_half_pose_diff");
    std::printf("requests_rho_abs_diff_mean %.5f\nrequests_rho_abs_diff_max %.5f\n", drho.mean(), drho.maxCoeff());

    // Held-out samples: both systems on the others, each prediction against the sample itself.
    const MatX xc = exact.scaling().apply(exact.sample_parameters());
    const MatX& u = exact.set_model().tucker.U[2];
    std::vector<Eigen::Index> train, test;
    for (Eigen::Index i = 0; i < n; ++i) (i % holdout == holdout / 2 ? test : train).push_back(i);
    MatX x_train(static_cast<Eigen::Index>(train.size()), xc.cols()), u_train(x_train.rows(), u.cols());
    for (std::size_t r = 0; r < train.size(); ++r) {
        x_train.row(static_cast<Eigen::Index>(r)) = xc.row(train[r]);
        u_train.row(static_cast<Eigen::Index>(r)) = u.row(train[r]);
    }
    t0 = Clock::now();
    const kriging::Kriging ke = kriging::Kriging::build(x_train, exact.report().model, exact.kriging_options());
    const double build_exact_s = seconds_since(t0);
    const kriging::LocalKriging kl =
        kriging::LocalKriging::build(x_train, exact.report().model, exact.kriging_options(), k);
    Gaps local_vs_exact, exact_vs_truth, local_vs_truth;
    double hrel_sum = 0.0, hrel_max = 0.0, hrho_sum = 0.0, hrho_max = 0.0;
    for (const Eigen::Index i : test) {
        const VecX ci = xc.row(i).transpose();
        const kriging::KrigingEstimate ee = ke.estimate(ci), el = kl.estimate(ci);
        ue = u_train.transpose() * ee.weights;
        ul = u_train.transpose() * el.weights;
        const double rel = (ul - ue).norm() / std::max(ue.norm(), 1e-300);
        hrel_sum += rel;
        hrel_max = std::max(hrel_max, rel);
        const double dr = std::abs(ee.reliability - el.reliability);
        hrho_sum += dr;
        hrho_max = std::max(hrho_max, dr);
        const MatX pe = positions(exact, ue), pl = positions(exact, ul), pt = positions(exact, u.row(i).transpose());
        local_vs_exact.add(gap(pe, pl));
        exact_vs_truth.add(gap(pe, pt));
        local_vs_truth.add(gap(pl, pt));
    }
    std::printf("heldout_samples %zu\nheldout_exact_build_s %.3f\n", test.size(), build_exact_s);
    std::printf("heldout_coefficients_rel_diff_mean %.5f\nheldout_coefficients_rel_diff_max %.5f\n",
                hrel_sum / static_cast<double>(test.size()), hrel_max);
    local_vs_exact.print("heldout_local_vs_exact");
    exact_vs_truth.print("heldout_exact_error");
    local_vs_truth.print("heldout_local_error");
    std::printf("heldout_rho_abs_diff_mean %.5f\nheldout_rho_abs_diff_max %.5f\n",
                hrho_sum / static_cast<double>(test.size()), hrho_max);
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 3) {
        std::fprintf(stderr, "usage: bench_synthesis_scale DB.h5 SET [queries=200] [subset | local [k=300] [holdout=20]]\n");
        return 2;
    }
    const std::string name = argv[2];
    const int queries = argc > 3 ? std::max(1, std::atoi(argv[3])) : 200;
    const std::string mode = argc > 4 ? argv[4] : "subset";
    const Database db(argv[1]);
    if (mode == "local") {
        const int k = argc > 5 ? std::max(1, std::atoi(argv[5])) : 300;
        const int holdout = argc > 6 ? std::max(2, std::atoi(argv[6])) : 20;
        return local_mode(db, name, queries, k, holdout);
    }
    return subset_mode(db, name, queries);
}
