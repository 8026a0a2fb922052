// Kriging engine timings (issue "Kriging engine", acceptance 3):
//   factorization (Kriging::build) for N = 92 and N = 1000 control points,
//   weights of one query for N = 92, P = 4 (target <= 1 us for every variogram model; with AVX2 + FMA
//   through the packed symmetric operator of lib/src/kriging/query_kernels.hpp),
//   weights of a batch of 10 000 queries,
//   and the folded predictor (24 values per sample folded into the operator) per query and per batch.
// Plain executable; prints one "key value unit" line per figure. Usage: bench_kriging [repeats]
#include "bench_timing.hpp"
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <random>
#include <string>
#include <vector>

#include "mocapdb/kriging/kriging.hpp"
#include "mocapdb/kriging/kriging_predictor.hpp"
#include "mocapdb/kriging/rbf.hpp"

using namespace mocapdb::kriging;

using namespace mocapdb::bench;

namespace {

// Seconds per single-query weights call of each interpolator (queries: P by 4096), one figure per chunk
// of 2000 calls, 50 chunks per repeat. The interpolators take turns chunk by chunk, so a slow phase of
// the shared machine (they last seconds here) falls on all of them alike: the best chunk is the
// undisturbed speed and the median shows the interference.
std::vector<std::vector<double>> per_query_seconds(const std::vector<const Interpolator*>& interps,
                                                   const Eigen::MatrixXd& queries, int repeats) {
    QueryWorkspace ws;
    const int iters = 2000;
    std::vector<std::vector<double>> t(interps.size());
    int i = 0;
    for (int r = 0; r < repeats * 50; ++r)
        for (std::size_t j = 0; j < interps.size(); ++j) {
            Eigen::VectorXd w(interps[j]->num_samples());
            const auto t0 = Clock::now();
            for (int k = 0; k < iters; ++k, ++i) {
                interps[j]->weights(queries.col(i & 4095), w, ws);
                g_sink = g_sink + w(i % w.size());
            }
            t[j].push_back(seconds_since(t0) / iters);
        }
    return t;
}


// CPU time of the calling thread (excludes the time other processes of the shared machine had the core).
Eigen::MatrixXd uniform(Eigen::Index n, Eigen::Index p, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> ud(0.0, 1.0);
    Eigen::MatrixXd m(n, p);
    for (Eigen::Index k = 0; k < m.size(); ++k) m.data()[k] = ud(rng);
    return m;
}




}  // namespace

int main(int argc, char** argv) {
    const int repeats = argc > 1 ? std::max(1, std::atoi(argv[1])) : 5;
    const Eigen::Index p = 4;
    const VariogramModel stable = VariogramModel::stable(1.5, 0.01, 1.0, 0.5);
    // Every code path of the variogram values: spherical, the special-cased exponents 1, 1.5 and 0.5
    // (square roots), 2, and general exponents of the fitting grid (1.4 and 0.2: exp(p log x), then exp).
    const VariogramModel models[] = {VariogramModel::spherical(0.01, 1.0, 0.8), VariogramModel::stable(1.0, 0.01, 1.0, 0.5),
                                     stable, VariogramModel::stable(0.5, 0.01, 1.0, 0.5),
                                     VariogramModel::stable(1.4, 0.01, 1.0, 0.5), VariogramModel::stable(0.2, 0.01, 1.0, 0.5),
                                     VariogramModel::stable(2.0, 0.01, 1.0, 0.5)};
    KrigingOptions ols;  // the paper's default: linear trend by OLS + ordinary-kriging kernel
    KrigingOptions gls;
    gls.trend_fit = TrendFit::GLS;

    std::printf("# bench_kriging: P = %d, model stable(p=1.5) unless noted, best of %d repeats (median in brackets;\n"
                "# per-query figures: best and median of 50 x repeats chunks of 2000 queries, the models taking turns)\n",
                static_cast<int>(p), repeats);
    // 1. Factorization.
    for (Eigen::Index n : {Eigen::Index{92}, Eigen::Index{1000}}) {
        const Eigen::MatrixXd pts = uniform(n, p, 1);
        for (const auto* opt : {&ols, &gls}) {
            std::vector<double> t;
            for (int r = 0; r < repeats; ++r) {
                const auto t0 = Clock::now();
                const Kriging k = Kriging::build(pts, stable, *opt);
                t.push_back(seconds_since(t0));
                g_sink = g_sink + k.status().rcond;
            }
            std::printf("factorize_N%d_%s %.3f ms (median %.3f)\n", static_cast<int>(n), to_string(opt->trend_fit), 1e3 * best(t),
                        1e3 * median(t));
        }
    }
    // 2. Single-query weights, N = 92.
    {
        const Eigen::Index n = 92;
        const Eigen::MatrixXd pts = uniform(n, p, 2);
        // One query per column (contiguous), as a caller holding its control vectors would pass them.
        const Eigen::MatrixXd queries = uniform(4096, p, 3).transpose();
        std::vector<Kriging> krigings;
        std::vector<std::string> names;
        for (const auto& model : models)
            for (const auto* opt : {&ols, &gls}) {
                krigings.push_back(Kriging::build(pts, model, *opt));
                names.push_back("weights_per_query_N92_P4_" +
                                (model.family == VariogramFamily::Spherical ? std::string("sph")
                                                                            : "stable" + std::to_string(model.exponent).substr(0, 3)) +
                                "_" + to_string(opt->trend_fit));
            }
        // RBF baseline, same interface.
        const RbfInterpolator rbf = RbfInterpolator::build(pts, {});
        std::vector<const Interpolator*> interps;
        for (const auto& k : krigings) interps.push_back(&k);
        interps.push_back(&rbf);
        names.push_back("rbf_weights_per_query_N92_P4");
        const auto t = per_query_seconds(interps, queries, repeats);
        for (std::size_t j = 0; j < interps.size(); ++j)
            std::printf("%s %.1f ns (median %.1f)\n", names[j].c_str(), 1e9 * best(t[j]), 1e9 * median(t[j]));
    }
    // 3. Batch of 10 000 queries (weights matrix N by 10 000), N = 92 and N = 1000.
    for (Eigen::Index n : {Eigen::Index{92}, Eigen::Index{1000}}) {
        const Eigen::MatrixXd pts = uniform(n, p, 4);
        const Eigen::MatrixXd queries = uniform(10000, p, 5);
        for (const auto* opt : {&ols, &gls}) {
            const Kriging k = Kriging::build(pts, stable, *opt);
            Eigen::MatrixXd w(n, queries.rows());
            std::vector<double> t, cpu;
            // A batch takes several ms at N = 92, longer than the scheduler gives a process on a loaded
            // machine: 10 x repeats runs, each timed by the wall clock and by the thread's CPU time (the
            // per-query figures' 2 ms chunks can fall between two other processes, a batch cannot).
            const int runs = n > 100 ? repeats : 10 * repeats;
            for (int r = 0; r < runs; ++r) {
                const double c0 = thread_cpu_seconds();
                const auto t0 = Clock::now();
                k.weights_batch(queries, w);
                t.push_back(seconds_since(t0));
                cpu.push_back(thread_cpu_seconds() - c0);
                g_sink = g_sink + w(0, 0);
            }
            std::printf("batch10000_weights_N%d_%s %.3f ms (%.1f ns per query; median %.3f ms; CPU time best %.1f ns per "
                        "query)\n", static_cast<int>(n), to_string(opt->trend_fit), 1e3 * best(t), 1e9 * best(t) / 10000.0,
                        1e3 * median(t), 1e9 * best(cpu) / 10000.0);
        }
    }
    // Full estimates (weights + variance + reliability) for the batch, N = 92.
    {
        const Eigen::MatrixXd pts = uniform(92, p, 6);
        const Eigen::MatrixXd queries = uniform(10000, p, 7);
        for (const auto* opt : {&ols, &gls}) {
            const Kriging k = Kriging::build(pts, stable, *opt);
            std::vector<double> t;
            for (int r = 0; r < 10 * repeats; ++r) {
                const auto t0 = Clock::now();
                const KrigingBatch b = k.estimate_batch(queries);
                t.push_back(seconds_since(t0));
                g_sink = g_sink + b.reliability(0);
            }
            std::printf("batch10000_estimate_N92_%s %.3f ms (median %.3f)\n", to_string(opt->trend_fit), 1e3 * best(t), 1e3 * median(t));
        }
    }
    // 4. Folded predictor (kriging_predictor.hpp): 24 values per sample (the synthesis model's R3) folded
    //    into the operator, N = 92, P = 4, per query and per batch of 10 000, for the same models.
    {
        const Eigen::MatrixXd pts = uniform(92, p, 2);
        const Eigen::MatrixXd values = uniform(92, 24, 8);
        const Eigen::MatrixXd queries = uniform(4096, p, 3).transpose();
        const Eigen::MatrixXd batch_queries = uniform(10000, p, 5);
        for (const auto& model : models) {
            const KrigingPredictor kp = KrigingPredictor::build(Kriging::build(pts, model, ols), values);
            QueryWorkspace ws;
            Eigen::VectorXd out(24);
            std::vector<double> t;
            int i = 0;
            for (int r = 0; r < repeats * 50; ++r) {
                const auto t0 = Clock::now();
                for (int k = 0; k < 2000; ++k, ++i) {
                    kp.predict(queries.col(i & 4095), out, ws);
                    g_sink = g_sink + out(i % 24);
                }
                t.push_back(seconds_since(t0) / 2000);
            }
            const std::string name = model.family == VariogramFamily::Spherical
                                         ? std::string("sph")
                                         : "stable" + std::to_string(model.exponent).substr(0, 3);
            std::printf("folded24_per_query_N92_P4_%s_ols %.1f ns (median %.1f)\n", name.c_str(), 1e9 * best(t),
                        1e9 * median(t));
            Eigen::MatrixXd o(24, batch_queries.rows()), scratch;
            std::vector<double> tb, cpu;
            for (int r = 0; r < 10 * repeats; ++r) {
                const double c0 = thread_cpu_seconds();
                const auto t0 = Clock::now();
                kp.predict_batch(batch_queries, o, scratch);
                tb.push_back(seconds_since(t0));
                cpu.push_back(thread_cpu_seconds() - c0);
                g_sink = g_sink + o(0, 0);
            }
            std::printf("folded24_batch10000_N92_%s_ols %.3f ms (%.1f ns per query; median %.3f ms; CPU time best %.1f ns "
                        "per query)\n", name.c_str(), 1e3 * best(tb), 1e9 * best(tb) / 10000.0, 1e3 * median(tb),
                        1e9 * best(cpu) / 10000.0);
        }
    }
    std::printf("# sink %g\n", static_cast<double>(g_sink));
    return 0;
}
