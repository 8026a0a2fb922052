// Synthesis timings (issue #6, acceptance 4), the compressed model (Tucker + kriging of the sample-mode
// coefficients) and the naive one (kriging of the uncompressed aligned tensor) side by side:
//   precompute time, memory per loaded model,
//   microseconds per pose on one thread: pose(c, t) from control parameters (kriging + pose) and from a
//       character's prepared coefficient vector, at full ranks and a lower level of detail,
//   batched poses per second on 2 threads (Q characters per call),
//   and how far the compressed poses are from the naive ones (joint positions, cm).
// Data: the paper's sizes, D x T x N ~ 94 x 100 x 92, P = 4, ranks 22 x 6 x 24. Poses are real: subject
// 16's walks (D = 90 dofs) linearly aligned to 100 frames, blended smoothly over a random 4-D parameter
// space into 92 samples (plus 0.01 rad noise so the sample mode has full rank), with durations that
// vary with the parameters.
// Plain executable; prints one "key value unit" line per figure. Usage: bench_synthesis [repeats]
#include "bench_timing.hpp"

#include <algorithm>
#include <cstdio>
#include <ctime>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "mocapdb/compression/dof_weights.hpp"
#include "mocapdb/compression/set_model.hpp"
#include "mocapdb/dataset/alignment.hpp"
#include "mocapdb/compression/joint_error.hpp"
#include "mocapdb/io/clip_file.hpp"
#include "mocapdb/synthesis/motion_model.hpp"
#include "mocapdb/synthesis/naive_motion_model.hpp"

using namespace mocapdb;
using namespace mocapdb::bench;
using namespace mocapdb::synthesis;

namespace {

struct BenchSet {
    AlignedSet aligned;
    MotionSet set;
    std::shared_ptr<const Skeleton> skeleton;
};

BenchSet make_set(Eigen::Index n, Eigen::Index p, Eigen::Index frames) {
    const std::filesystem::path dir = std::filesystem::path(MOCAPDB_SHARED_DIR) / "datasets" / "cmu-asfamc";
    std::vector<Clip> clips;
    for (int t = 11; t <= 22; ++t) clips.push_back(read_clip(dir / ("16_" + std::to_string(t) + ".amc")));
    AlignOptions ao;
    ao.method = "linear";
    ao.frames = frames;
    const AlignedSet base = align_samples(clips, ao);
    const Eigen::Index d = base.dofs(), k_count = base.samples();

    std::mt19937 rng(7);
    std::uniform_real_distribution<double> ud(0.0, 1.0);
    std::normal_distribution<double> nd(0.0, 0.01);
    MatX c(n, p), anchors(k_count, p);
    for (Eigen::Index i = 0; i < c.size(); ++i) c.data()[i] = ud(rng);
    for (Eigen::Index i = 0; i < anchors.size(); ++i) anchors.data()[i] = ud(rng);

    BenchSet b;
    b.skeleton = clips.front().skeleton;
    b.aligned.method = "linear";
    b.aligned.tensor = Tensor3(d, frames, n);
    b.aligned.warps.resize(frames, n);
    b.aligned.canonical.resize(static_cast<std::size_t>(n));
    b.set.name = "bench";
    b.set.parameters = c;
    for (Eigen::Index k = 0; k < p; ++k) {
        b.set.parameter_names.push_back("p" + std::to_string(k));
        b.set.parameter_units.push_back("");
    }
    for (Eigen::Index i = 0; i < n; ++i) {
        VecX phi(k_count);
        for (Eigen::Index k = 0; k < k_count; ++k) phi(k) = std::exp(-(c.row(i) - anchors.row(k)).squaredNorm() / 0.1);
        phi /= phi.sum();
        for (Eigen::Index t = 0; t < frames; ++t)
            for (Eigen::Index q = 0; q < d; ++q) {
                double v = 0.0;
                for (Eigen::Index k = 0; k < k_count; ++k) v += phi(k) * base.tensor(q, t, k);
                b.aligned.tensor(q, t, i) = v + nd(rng);
            }
        const double length = 100.0 + 40.0 * c(i, 0) + 10.0 * c(i, 1);
        for (Eigen::Index t = 0; t < frames; ++t)
            b.aligned.warps(t, i) = static_cast<double>(t) * (length - 1.0) / static_cast<double>(frames - 1);
        b.set.samples.push_back({"s" + std::to_string(i), 0, static_cast<std::size_t>(length)});
    }
    b.aligned.mean = compression::dof_means(b.aligned.tensor);
    b.aligned.scale = VecX::Ones(d);
    return b;
}

MatX random_queries(Eigen::Index q, Eigen::Index p, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> ud(0.05, 0.95);
    MatX m(q, p);
    for (Eigen::Index i = 0; i < m.size(); ++i) m.data()[i] = ud(rng);
    return m;
}

// CPU time of the calling thread (excludes the time other processes of the shared machine had the core).
double thread_cpu_seconds() {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// Best microseconds per call over chunks of `iters` calls (a shared machine: the best chunk is the
// undisturbed speed), and the median.
template <class F>
std::pair<double, double> per_call_us(int repeats, int iters, F fn) {
    std::vector<double> t;
    int i = 0;
    for (int r = 0; r < repeats * 20; ++r) {
        const auto t0 = Clock::now();
        for (int k = 0; k < iters; ++k, ++i) fn(i);
        t.push_back(1e6 * seconds_since(t0) / iters);
    }
    return {best(t), median(t)};
}

void line(const std::string& key, double value, const char* unit) { std::printf("%-58s %12.4g %s\n", key.c_str(), value, unit); }

void bench_model(const SynthesisModel& m, const char* name, const MatX& C, const VecX& times, int repeats) {
    const Eigen::Index q_count = C.rows();
    const std::string k = std::string(name) + ".";
    line(k + "memory", static_cast<double>(m.memory_bytes()) / 1024.0, "KiB");
    for (Eigen::Index level = 0; level < m.levels(); ++level) {
        const tensor::Ranks r = m.level_ranks(level);
        const std::string lk = k + std::to_string(r[0]) + "x" + std::to_string(r[1]) + "x" + std::to_string(r[2]) + ".";
        Workspace ws;
        VecX out(m.dofs());
        const auto full = per_call_us(repeats, 2000, [&](int i) {
            const Eigen::Index q = i % q_count;
            m.pose(C.row(q).transpose(), times(q), out, ws, level);
            g_sink = g_sink + out(0);
        });
        line(lk + "pose_from_c_us (best, median " + std::to_string(full.second).substr(0, 5) + ")", full.first, "us");
        // A crowd: each character's coefficient vector computed once.
        MatX coef(m.coefficient_size(), q_count);
        for (Eigen::Index q = 0; q < q_count; ++q) m.coefficients(C.row(q).transpose(), coef.col(q), ws);
        const auto prepared = per_call_us(repeats, 5000, [&](int i) {
            const Eigen::Index q = i % q_count;
            m.pose_from_coefficients(coef.col(q), times(q), out, ws, level);
            g_sink = g_sink + out(0);
        });
        line(lk + "pose_from_coefficients_us (best, median " + std::to_string(prepared.second).substr(0, 5) + ")",
             prepared.first, "us");
        const auto kriging = per_call_us(repeats, 2000, [&](int i) {
            const Eigen::Index q = i % q_count;
            m.coefficients(C.row(q).transpose(), coef.col(q), ws);
        });
        line(lk + "coefficients_from_c_us", kriging.first, "us");

        // Batched: `threads` threads, each synthesizing `batch` characters per call at one frame.
        const Eigen::Index batch = 1024;
        for (int threads_n : {1, 2}) {
            for (int prepared_mode = 0; prepared_mode < 2; ++prepared_mode) {
                // Per thread: its characters' parameters and coefficients (set up before the clock starts).
                std::vector<MatX> cb(2), cf(2);
                for (int th = 0; th < 2; ++th) {
                    cb[static_cast<std::size_t>(th)] = C.middleRows(th * batch, batch);
                    cf[static_cast<std::size_t>(th)].resize(m.coefficient_size(), batch);
                    for (Eigen::Index q = 0; q < batch; ++q)
                        m.coefficients(cb[static_cast<std::size_t>(th)].row(q).transpose(),
                                       cf[static_cast<std::size_t>(th)].col(q), ws);
                }
                double best_rate = 0.0, best_cpu_rate = 0.0;
                for (int rep = 0; rep < repeats * 3; ++rep) {
                    const int calls = prepared_mode ? 200 : 20;
                    std::vector<double> cpu(static_cast<std::size_t>(threads_n), 0.0);
                    const auto t0 = Clock::now();
                    std::vector<std::thread> threads;
                    for (int th = 0; th < threads_n; ++th)
                        threads.emplace_back([&, th] {
                            BatchWorkspace bws;
                            MatX poses(m.dofs(), batch);
                            const auto s = static_cast<std::size_t>(th);
                            const double c0 = thread_cpu_seconds();
                            for (int call = 0; call < calls; ++call) {
                                const double t = static_cast<double>((call * 7 + th) % (m.frames() - 1)) + 0.5;
                                if (prepared_mode) m.poses_from_coefficients(cf[s], t, poses, bws, level);
                                else m.poses(cb[s], t, poses, bws, level);
                            }
                            cpu[s] = thread_cpu_seconds() - c0;
                            g_sink = g_sink + poses(0, 0);
                        });
                    for (auto& th : threads) th.join();
                    const double poses_done = threads_n * calls * static_cast<double>(batch);
                    best_rate = std::max(best_rate, poses_done / seconds_since(t0));
                    best_cpu_rate = std::max(best_cpu_rate, poses_done / *std::max_element(cpu.begin(), cpu.end()));
                }
                const std::string key = lk + "batch_" + std::to_string(threads_n) + "threads_" +
                                        (prepared_mode ? "from_coefficients" : "from_c");
                line(key, best_rate / 1e6, "M poses/s");
                // The same runs rated by the busiest thread's CPU time (time it was actually running): what
                // the threads achieve when each has a core, whatever else the shared machine runs.
                line(key + "_cpu_time", best_cpu_rate / 1e6, "M poses/s");
            }
        }
    }
}

}  // namespace

int main(int argc, char** argv) {
    const int repeats = argc > 1 ? std::max(1, std::atoi(argv[1])) : 3;
    const Eigen::Index n = 92, p = 4, frames = 100;
    const auto t_data = Clock::now();
    const BenchSet b = make_set(n, p, frames);
    std::printf("# data: %lld dofs x %lld frames x %lld samples, P = %lld (built in %.2f s)\n",
                static_cast<long long>(b.aligned.dofs()), static_cast<long long>(frames), static_cast<long long>(n),
                static_cast<long long>(p), seconds_since(t_data));
    const VecX weight = compression::position_error_weights(*b.skeleton);

    compression::SetModel sm;
    const double hosvd_s = best_of(repeats, [&] {
        sm = compression::fit_set_model(b.aligned.tensor, weight, {22, 6, 24}, tensor::TuckerMethod::Hosvd);
    });
    SynthesisOptions options;
    options.levels = {{11, 4, 12}};
    std::unique_ptr<MotionModel> model;
    const double model_s = best_of(repeats, [&] {
        model = std::make_unique<MotionModel>(sm, b.aligned, b.set, b.skeleton, 120.0, options);
    });
    std::unique_ptr<NaiveMotionModel> naive;
    const double naive_s = best_of(repeats, [&] {
        naive = std::make_unique<NaiveMotionModel>(b.aligned, b.set, b.skeleton, 120.0, weight);
    });
    line("precompute.hosvd_22x6x24", hosvd_s, "s");
    line("precompute.tucker_model (kriging + timing + evaluators)", model_s, "s");
    line("precompute.tucker_total", hosvd_s + model_s, "s");
    line("precompute.naive_model (kriging + timing)", naive_s, "s");
    std::printf("# tucker kernel: %s; naive kernel: %s\n", model->report().model.to_string().c_str(),
                naive->report().model.to_string().c_str());

    const Eigen::Index q_count = 4096;
    const MatX C = random_queries(q_count, p, 11);
    VecX times(q_count);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> ut(0.0, static_cast<double>(frames - 1));
    for (Eigen::Index q = 0; q < q_count; ++q) times(q) = ut(rng);

    bench_model(*model, "tucker", C, times, repeats);
    bench_model(*naive, "naive", C, times, repeats);

    // Accuracy of the compressed poses against the naive ones (the paper's ground truth), 500 queries.
    const Eigen::Index acc = 500;
    MatX qc(model->dofs(), acc), qn(model->dofs(), acc), ql(model->dofs(), acc);
    Workspace ws;
    for (Eigen::Index q = 0; q < acc; ++q) {
        model->pose(C.row(q).transpose(), times(q), qc.col(q), ws);
        model->pose(C.row(q).transpose(), times(q), ql.col(q), ws, 1);
        naive->pose(C.row(q).transpose(), times(q), qn.col(q), ws);
    }
    const MatX jc = compression::pose_joint_positions(*b.skeleton, qc), jl = compression::pose_joint_positions(*b.skeleton, ql),
               jn = compression::pose_joint_positions(*b.skeleton, qn);
    const auto joint_rmse = [&](const MatX& a) {
        double s = 0.0, mx = 0.0;
        for (Eigen::Index q = 0; q < a.cols(); ++q)
            for (Eigen::Index j = 0; j < a.rows() / 3; ++j) {
                const double e = (a.block<3, 1>(3 * j, q) - jn.block<3, 1>(3 * j, q)).squaredNorm();
                s += e;
                mx = std::max(mx, std::sqrt(e));
            }
        return std::make_pair(std::sqrt(s / static_cast<double>(a.cols() * (a.rows() / 3))), mx);
    };
    const auto e22 = joint_rmse(jc), e11 = joint_rmse(jl);
    line("accuracy.tucker_22x6x24_vs_naive.joint_rmse", e22.first, "cm");
    line("accuracy.tucker_22x6x24_vs_naive.joint_max", e22.second, "cm");
    line("accuracy.tucker_11x4x12_vs_naive.joint_rmse", e11.first, "cm");
    line("accuracy.tucker_11x4x12_vs_naive.joint_max", e11.second, "cm");
    return 0;
}
