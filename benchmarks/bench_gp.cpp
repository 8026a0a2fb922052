// MOHGP timings (issue "Hierarchical multi-output Gaussian processes", acceptance 4):
//   one log likelihood + gradient evaluation, structured (1 and 2 threads) vs dense, by size;
//   training time for 3 children × 39 outputs × 90 frames (CMU walks 02_01, 02_02, 35_01; target ≤ 60 s);
//   per-evaluation time at larger D·T (two layers, and three layers with equal and unequal groups), from which the largest problem trainable in 10 minutes is
//   estimated (evaluations needed × seconds per evaluation).
// Plain executable; prints one "key value unit" line per figure.
// Usage: bench_gp [max_iterations=300] [q=1] [--no-train] [--no-structured] [--sizes N1,N2,...] [--train-dofs K=39]
//                 [--train-frames N=90] [--mohgp-only]
#include "bench_timing.hpp"

#include <cstdio>
#include <ctime>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "mocapdb/core/keep_freed_memory.hpp"
#include "mocapdb/gp/motion_data.hpp"
#include "mocapdb/gp/optimize.hpp"
#include "mocapdb/io/clip_file.hpp"

using namespace mocapdb;
using namespace mocapdb::gp;
using namespace mocapdb::bench;

namespace {

HgpData synthetic(Eigen::Index d, Eigen::Index t, std::size_t r) {
    std::mt19937_64 rng(7);
    std::normal_distribution<double> normal(0.0, 1.0);
    HgpData data;
    data.times = VecX::LinSpaced(t, 0.0, 2.5);
    for (std::size_t c = 0; c < r; ++c) {
        MatX y(d, t);
        for (Eigen::Index i = 0; i < d; ++i)
            for (Eigen::Index f = 0; f < t; ++f)
                y(i, f) = 0.5 + 0.3 * std::sin(5.0 * data.times[f] + 0.3 * static_cast<double>(i)) + 0.05 * normal(rng);
        data.children.push_back(y);
    }
    return data;
}

double eval_seconds(const HgpModel& m, const HgpData& data, LikelihoodPath path, int threads, int repeats) {
    return best_of(repeats, [&] {
        const LikelihoodValue v = log_likelihood(m, data, true, path, threads);
        g_sink = g_sink + v.log_likelihood;
    });
}

}  // namespace

int main(int argc, char** argv) {
    keep_freed_memory();  // as `mocapdb gp` does
    int max_iterations = 300;
    std::size_t q = 1;
    bool train = true;
    bool structured = true;  // also time the (D·T)² structured path at the large sizes
    Eigen::Index train_dofs = 39;
    std::size_t train_frames = 90;
    bool moa = true;
    std::vector<Eigen::Index> sizes = {1000, 2000, 3510, 5000};
    int positional = 0;
    for (int i = 1; i < argc; ++i) {
        if (std::strcmp(argv[i], "--no-train") == 0) {
            train = false;
        } else if (std::strcmp(argv[i], "--no-structured") == 0) {
            structured = false;
        } else if (std::strcmp(argv[i], "--train-dofs") == 0 && i + 1 < argc) {
            train_dofs = std::atol(argv[++i]);
        } else if (std::strcmp(argv[i], "--train-frames") == 0 && i + 1 < argc) {
            train_frames = static_cast<std::size_t>(std::atol(argv[++i]));
        } else if (std::strcmp(argv[i], "--mohgp-only") == 0) {
            moa = false;
        } else if (std::strcmp(argv[i], "--sizes") == 0 && i + 1 < argc) {
            sizes.clear();
            for (char* tok = std::strtok(argv[++i], ","); tok; tok = std::strtok(nullptr, ","))
                sizes.push_back(std::atol(tok));
        } else if (positional == 0) {
            max_iterations = std::atoi(argv[i]);
            ++positional;
        } else {
            q = static_cast<std::size_t>(std::atoi(argv[i]));
        }
    }
    ModelSpec spec;
    spec.kernel = KernelType::Matern32;
    spec.parent_terms = spec.child_terms = q;

    // 1. One evaluation: structured vs dense, small sizes (dense is the O((R·D·T)³) oracle).
    for (Eigen::Index d : {4, 8}) {
        const HgpData data = synthetic(d, 30, 3);
        const HgpModel m = initial_model(data, spec);
        std::printf("eval_dense D=%lld T=30 R=3 n=%lld params=%zu: %.4f s\n", static_cast<long long>(d),
                    static_cast<long long>(3 * d * 30), m.parameter_count(), eval_seconds(m, data, LikelihoodPath::Dense, 1, 2));
        std::printf("eval_structured D=%lld T=30 R=3 threads=1: %.5f s\n", static_cast<long long>(d),
                    eval_seconds(m, data, LikelihoodPath::Structured, 1, 3));
        std::printf("eval_lowrank D=%lld T=30 R=3 threads=1: %.5f s\n", static_cast<long long>(d),
                    eval_seconds(m, data, LikelihoodPath::LowRank, 1, 3));
    }
    // 2. Per-evaluation time of the structured path by n = D·T (T = 90), 1 and 2 threads.
    for (Eigen::Index n : sizes) {
        const Eigen::Index d = std::max<Eigen::Index>(1, n / 90);
        const HgpData data = synthetic(d, 90, 3);
        const HgpModel m = initial_model(data, spec);
        if (structured) {
            const double t1 = eval_seconds(m, data, LikelihoodPath::Structured, 1, 1);
            const double t2 = eval_seconds(m, data, LikelihoodPath::Structured, 2, 2);
            std::printf("eval_structured D=%lld T=90 R=3 n=%lld params=%zu: %.3f s (1 thread) %.3f s (2 threads)\n",
                        static_cast<long long>(d), static_cast<long long>(d * 90), m.parameter_count(), t1, t2);
        }
        const double l1 = eval_seconds(m, data, LikelihoodPath::LowRank, 1, 3);
        const double l2 = eval_seconds(m, data, LikelihoodPath::LowRank, 2, 3);
        std::printf("eval_lowrank D=%lld T=90 R=3 n=%lld params=%zu: %.4f s (1 thread) %.4f s (2 threads)\n",
                    static_cast<long long>(d), static_cast<long long>(d * 90), m.parameter_count(), l1, l2);
    }
    // 2b. Three layers (trend → group → child) at the same sizes: equal groups {0,0,1,1} and unequal
    // groups {0,0,1} (the coupled size classes).
    for (Eigen::Index n : sizes) {
        const Eigen::Index d = std::max<Eigen::Index>(1, n / 90);
        ModelSpec s3 = spec;
        s3.grouped = true;
        s3.group_terms = q;
        HgpData equal = synthetic(d, 90, 4);
        equal.groups = {0, 0, 1, 1};
        const HgpModel m = initial_model(equal, s3);
        std::printf("eval_lowrank_3layers D=%lld T=90 R=4 groups=2x2 params=%zu: %.4f s (1 thread) %.4f s (2 threads)\n",
                    static_cast<long long>(d), m.parameter_count(), eval_seconds(m, equal, LikelihoodPath::LowRank, 1, 3),
                    eval_seconds(m, equal, LikelihoodPath::LowRank, 2, 3));
        HgpData unequal = synthetic(d, 90, 3);
        unequal.groups = {0, 0, 1};
        std::printf("eval_lowrank_3layers D=%lld T=90 R=3 groups=2+1 (coupled): %.4f s (1 thread) %.4f s (2 threads)\n",
                    static_cast<long long>(d), eval_seconds(m, unequal, LikelihoodPath::LowRank, 1, 3),
                    eval_seconds(m, unequal, LikelihoodPath::LowRank, 2, 3));
        if (structured)
            std::printf("eval_structured_3layers D=%lld T=90 R=3 groups=2+1 (coupled): %.3f s (2 threads)\n",
                        static_cast<long long>(d), eval_seconds(m, unequal, LikelihoodPath::Structured, 2, 1));
    }
    if (!train) return 0;
    // 3. Training: 3 children × 39 outputs × 90 frames of CMU walks.
    const auto dir = std::filesystem::path(MOCAPDB_SHARED_DIR) / "datasets" / "cmu-asfamc";
    HgpData data;
    std::string source;
    if (std::filesystem::exists(dir / "35_01.amc")) {
        std::vector<Clip> clips;
        std::vector<std::string> names = {"02_01", "02_02", "35_01"};
        for (const auto& n : names) clips.push_back(read_clip(dir / (n + ".amc")));
        MotionDataOptions o;
        o.frames = train_frames;
        const MotionData md = prepare_motion_data(clips, names, o);
        data.times = md.data.times;
        const Eigen::Index d = std::min<Eigen::Index>(train_dofs, static_cast<Eigen::Index>(md.dofs.size()));
        for (const MatX& y : md.data.children) data.children.push_back(y.topRows(d));
        source = "CMU 02_01, 02_02, 35_01 (first " + std::to_string(d) + " of " + std::to_string(md.dofs.size()) +
                 " selected dofs)";
    } else {
        data = synthetic(train_dofs, static_cast<Eigen::Index>(train_frames), 3);
        source = "synthetic (shared data absent)";
    }
    for (bool hierarchical : {true, false}) {
        if (!hierarchical && !moa) break;
        spec.hierarchical = hierarchical;
        const HgpModel start = initial_model(data, spec);
        FitOptions f;
        f.max_iterations = max_iterations;
        const std::clock_t c0 = std::clock();
        const FitResult r = fit(data, start, f);
        const double cpu = static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
        std::printf("train %s %s, R=3 D=%zu T=%zu Q=%zu matern32, params=%zu: %.1f s (cpu %.1f s, all threads), %d evaluations "
                    "(%.2f s each), status %s, log likelihood %.2f (start %.2f)\n",
                    hierarchical ? "MOHGP" : "MOA", source.c_str(), data.outputs(), data.frames(), q,
                    start.parameter_count(), r.seconds, cpu, r.evaluations, r.seconds / std::max(1, r.evaluations),
                    to_string(r.status).c_str(), r.log_likelihood, log_likelihood(start, data, false).log_likelihood);
    }
    return 0;
}
