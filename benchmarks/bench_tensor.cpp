// Tucker decomposition timings (tensor module):
//   HOSVD, ST-HOSVD and HOOI of a random 94 x 100 x 92 tensor at ranks 22 x 6 x 24 (the sizes of the
//   multilinear motion paper; target <= 0.5 s each),
//   pose reconstruction per pose at those ranks (target <= 1 us), both evaluation orders of
//   PoseEvaluator: DofPrecomputed ((D x R2R3) * (u_sample (x) u_time)) and CoreFirst.
// Plain executable; prints one "key value unit" line per figure, best of the repeats (median in
// brackets). Usage: bench_tensor [repeats]
#include "bench_timing.hpp"
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

#include "mocapdb/tensor/hooi.hpp"
#include "mocapdb/tensor/hosvd.hpp"
#include "mocapdb/tensor/tucker.hpp"

using namespace mocapdb;
using namespace mocapdb::tensor;

using namespace mocapdb::bench;

namespace {



template <class F>
std::vector<double> time_runs(int repeats, F&& f) {
    std::vector<double> t;
    for (int r = 0; r < repeats; ++r) {
        const auto t0 = Clock::now();
        f();
        t.push_back(seconds_since(t0));
    }
    return t;
}

}  // namespace

int main(int argc, char** argv) {
    const int repeats = argc > 1 ? std::max(1, std::atoi(argv[1])) : 5;
    const Eigen::Index D = 94, T = 100, N = 92;
    const Ranks ranks{22, 6, 24};
    std::mt19937 rng(7);
    std::normal_distribution<double> nd(0.0, 1.0);
    Tensor3 a(D, T, N);
    for (Eigen::Index i = 0; i < a.size(); ++i) a.data()[i] = nd(rng);

    std::printf("# bench_tensor: random %d x %d x %d tensor, ranks %d x %d x %d, best of %d repeats (median in brackets)\n",
                static_cast<int>(D), static_cast<int>(T), static_cast<int>(N), static_cast<int>(ranks[0]),
                static_cast<int>(ranks[1]), static_cast<int>(ranks[2]), repeats);

    TuckerModel h, s, o;
    const auto th = time_runs(repeats, [&] { h = hosvd(a, ranks); });
    const auto ts = time_runs(repeats, [&] { s = st_hosvd(a, ranks); });
    const auto to = time_runs(repeats, [&] { o = hooi(a, ranks); });
    std::printf("hosvd_time %.4f s (%.4f)\n", best(th), median(th));
    std::printf("st_hosvd_time %.4f s (%.4f)\n", best(ts), median(ts));
    std::printf("hooi_time %.4f s (%.4f) sweeps %d status %s\n", best(to), median(to), o.iterations, to_string(o.status));
    std::printf("hosvd_relative_error %.6f measured, bound %.6f\n", relative_error(a, h), h.error_bound / h.data_norm);
    std::printf("st_hosvd_relative_error %.6f measured\n", relative_error(a, s));
    std::printf("hooi_relative_error %.6f measured\n", relative_error(a, o));
    std::printf("compression_ratio %.2f (parameters %ld of %ld)\n", h.compression_ratio(),
                static_cast<long>(h.parameter_count()), static_cast<long>(D * T * N));

    // Poses: every (t, n) of the model, coefficient rows copied to contiguous vectors beforehand (as an
    // interpolated time row or a kriged sample row would be).
    std::vector<Eigen::RowVectorXd> ut(static_cast<std::size_t>(T)), us(static_cast<std::size_t>(N));
    for (Eigen::Index t = 0; t < T; ++t) ut[static_cast<std::size_t>(t)] = o.U[1].row(t);
    for (Eigen::Index n = 0; n < N; ++n) us[static_cast<std::size_t>(n)] = o.U[2].row(n);
    const long poses = static_cast<long>(T * N) * 10;
    for (const auto order : {PoseEvaluator::Order::DofPrecomputed, PoseEvaluator::Order::CoreFirst}) {
        const PoseEvaluator ev(o, order);
        PoseEvaluator::Workspace ws;
        VecX q(D);
        const auto tp = time_runs(repeats, [&] {
            double acc = 0.0;
            for (int rep = 0; rep < 10; ++rep) {
                for (Eigen::Index n = 0; n < N; ++n) {
                    for (Eigen::Index t = 0; t < T; ++t) {
                        ev.evaluate(ut[static_cast<std::size_t>(t)], us[static_cast<std::size_t>(n)], q, ws);
                        acc += q(0);
                    }
                }
            }
            g_sink = acc;
        });
        std::printf("pose_time_%s %.3f us/pose (%.3f)\n",
                    order == PoseEvaluator::Order::DofPrecomputed ? "dof_precomputed" : "core_first",
                    best(tp) / static_cast<double>(poses) * 1e6, median(tp) / static_cast<double>(poses) * 1e6);
    }
    const PoseEvaluator automatic(o);
    std::printf("pose_auto_order %s\n",
                automatic.order() == PoseEvaluator::Order::DofPrecomputed ? "dof_precomputed" : "core_first");
    return 0;
}
