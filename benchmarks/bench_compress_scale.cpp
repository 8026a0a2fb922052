// `mocapdb compress --max-error-cm 1` at thousands of windows (issue #16): wall time and peak memory
// of the library steps the compress command runs, on a set of N windows of 60 frames cut from the
// shared CMU AMC clips (every clip whose pose vector has the first clip's layout; windows canonicalized
// one by one, start frames spread evenly over all clips so that N windows overlap as little as the
// data allows). With `distinct` < windows, only that many windows are cut and the set is filled with
// perturbed copies of them: copy c of window w is mean + s (w - mean) (mean: every dof's mean over the
// distinct windows, s uniform in [0.97, 1.03]) with its root moved by up to 2 cm in x and z -- a set of
// comparable samples, as `mocapdb set` groups them, rather than every kind of motion at once.
// Prints one `key value` line per figure.
//   bench_compress_scale [windows=10000] [distinct=windows] [frames=60] [max_error_cm=1]
// Steps timed (lib/src/workflow/set_compression.cpp, workflow::compress_set, without the database read and write):
// JointErrorMeter, prepare_set (HOSVD bases), search_ranks_for_max_error, the HOSVD at the chosen
// ranks and its errors (since #16 compress --method hosvd keeps the search's model and errors; build
// with -DMOCAPDB_BENCH_REFIT for fit_set_model and a second measure, the steps before),
// the measured error of the stored model, time_pose_evaluation. Peak memory: getrusage ru_maxrss of
// the whole process (the set itself included), and its value before the compression steps.
#include <sys/resource.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "bench_timing.hpp"
#include "mocapdb/compression/dof_weights.hpp"
#include "mocapdb/compression/rank_search.hpp"
#include "mocapdb/compression/rate_distortion.hpp"
#include "mocapdb/compression/set_model.hpp"
#include "mocapdb/compression/joint_error.hpp"
#include "mocapdb/io/clip_file.hpp"
#include "mocapdb/motion/pose_vector.hpp"

using namespace mocapdb;
using bench::Clock;
using bench::seconds_since;

namespace {

double peak_mb() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return static_cast<double>(u.ru_maxrss) / 1024.0;  // Linux: kilobytes
}

}  // namespace

int main(int argc, char** argv) {
    const Eigen::Index windows = argc > 1 ? std::max(3, std::atoi(argv[1])) : 10000;
    const Eigen::Index distinct = argc > 2 ? std::clamp<Eigen::Index>(std::atoi(argv[2]), 3, windows) : windows;
    const Eigen::Index frames = argc > 3 ? std::max(2, std::atoi(argv[3])) : 60;
    const double max_cm = argc > 4 ? std::atof(argv[4]) : 1.0;
    namespace fs = std::filesystem;
    const fs::path dir = fs::path(MOCAPDB_SHARED_DIR) / "datasets" / "cmu-asfamc";
    std::vector<fs::path> files;
    for (const auto& e : fs::directory_iterator(dir))
        if (e.path().extension() == ".amc") files.push_back(e.path());
    std::sort(files.begin(), files.end());

    const auto load_start = Clock::now();
    std::vector<Clip> clips;
    Eigen::Index dofs = -1, total = 0;
    for (const fs::path& f : files) {
        Clip c = read_clip(f);
        const auto d = static_cast<Eigen::Index>(PoseLayout(*c.skeleton).dof_count());
        if (dofs < 0) dofs = d;
        if (d != dofs || static_cast<Eigen::Index>(c.frame_count()) < frames) continue;
        total += static_cast<Eigen::Index>(c.frame_count()) - frames + 1;
        clips.push_back(std::move(c));
    }
    // Window k starts at position k * stride in the concatenation of every clip's valid start frames.
    const double stride = static_cast<double>(total) / static_cast<double>(distinct);
    Tensor3 poses(dofs, frames, windows);
    Eigen::Index k = 0, offset = 0;
    for (const Clip& c : clips) {
        const Eigen::Index starts = static_cast<Eigen::Index>(c.frame_count()) - frames + 1;
        for (; k < distinct; ++k) {
            const auto start = static_cast<Eigen::Index>(static_cast<double>(k) * stride) - offset;
            if (start >= starts) break;
            const Clip w = slice(c, static_cast<std::size_t>(start), static_cast<std::size_t>(start + frames));
            Eigen::Map<MatX>(poses.data() + k * dofs * frames, dofs, frames) = to_pose_vectors(w, canonicalization_of(w));
        }
        offset += starts;
    }
    {
        const Eigen::Map<const MatX> cut(poses.data(), dofs, frames * distinct);
        const VecX mean = cut.rowwise().mean();
        std::mt19937_64 rng(16);
        std::uniform_real_distribution<double> scale(0.97, 1.03), shift(-2.0, 2.0);
        for (; k < windows; ++k) {
            const Eigen::Map<const MatX> w(poses.data() + (k % distinct) * dofs * frames, dofs, frames);
            Eigen::Map<MatX> copy(poses.data() + k * dofs * frames, dofs, frames);
            copy = ((w.colwise() - mean) * scale(rng)).colwise() + mean;
            copy.row(0).array() += shift(rng);
            copy.row(2).array() += shift(rng);
        }
    }
    const std::shared_ptr<const Skeleton> skeleton = clips[0].skeleton;
    std::printf("set cmu_windows\nclips %zu\ndims %ld %ld %ld\ndistinct_windows %ld\nstride_frames %.2f\nload_s %.2f\n"
                "rss_after_load_mb %.0f\n",
                clips.size(), static_cast<long>(dofs), static_cast<long>(frames), static_cast<long>(windows),
                static_cast<long>(distinct), stride, seconds_since(load_start), peak_mb());
    std::fflush(stdout);
    clips.clear();
    clips.shrink_to_fit();

    // The steps of workflow::compress_set (lib/src/workflow/set_compression.cpp), target --max-error-cm.
    const auto start = Clock::now();
    auto t = Clock::now();
    const VecX weight = compression::position_error_weights(*skeleton);
    const compression::JointErrorMeter meter(skeleton, poses, compression::JointErrorMeter::Reference::Borrowed);
    std::printf("meter_s %.2f\n", seconds_since(t));
    t = Clock::now();
    const compression::PreparedSet prepared = compression::prepare_set(poses, weight);
    std::printf("prepare_set_s %.2f\nrss_after_prepare_mb %.0f\n", seconds_since(t), peak_mb());
    std::fflush(stdout);
    t = Clock::now();
    const compression::RankSearchResult chosen = compression::search_ranks_for_max_error(prepared, meter, max_cm);
    const tensor::Ranks r = chosen.model.tucker.ranks;
    std::printf("search_s %.2f\nsearch_evaluations %d\nsearch_full_checks %d\nranks %ld %ld %ld\nrss_after_search_mb %.0f\n", seconds_since(t),
                chosen.evaluations, chosen.full_checks, static_cast<long>(r[0]), static_cast<long>(r[1]), static_cast<long>(r[2]), peak_mb());
    std::fflush(stdout);
    t = Clock::now();
#ifdef MOCAPDB_BENCH_REFIT  // the pipeline before #16 decomposed the set again and measured it again
    const compression::SetModel model = compression::fit_set_model(poses, weight, r, tensor::TuckerMethod::Hosvd);
    std::printf("fit_s %.2f\n", seconds_since(t));
    t = Clock::now();
    const compression::JointErrorStats stats = meter.measure(model.reconstruct());
#else
    const compression::SetModel& model = chosen.model;  // compress --method hosvd since #16
    const compression::JointErrorStats stats = chosen.stats;
    std::printf("fit_s %.2f\n", seconds_since(t));
    t = Clock::now();
#endif
    std::printf("measure_s %.2f\nmax_cm %.4f\nrmse_cm %.4f\ntarget_met %d\n", seconds_since(t), stats.max_cm,
                stats.rmse_cm, stats.max_cm <= max_cm ? 1 : 0);
    t = Clock::now();
    const double us = compression::time_pose_evaluation(model.tucker);
    std::printf("pose_eval_us %.3f\npose_eval_timing_s %.2f\n", us, seconds_since(t));
    std::printf("compress_total_s %.2f\npeak_rss_mb %.0f\n", seconds_since(start), peak_mb());
    return 0;
}
