// Loading a stored synthesis model (issue #16: `synth` on a 645-sample set spent 19-29 s per call
// refitting its kernel): the steps of workflow::load_motion_model, timed one by one, with the kernel
// stored by `compress` (the default path) and without it (the variogram refitted, as before #16),
// then the first motion. The model reads the aligned set's timing and shape only (load_aligned_timing,
// as workflow::load_motion_model); the whole aligned set's read (tensor included, what the naive model
// needs) is timed too, outside load_total, for comparison. Wall time and process CPU time per step
// (the machine is shared: CPU time is the steadier figure); best of `repeats`. Prints one `key value`
// line per figure.
//   bench_synthesis_load DB.h5 SET v1,v2,... [repeats=3] [refit=1]
// The database: any set compressed by `mocapdb compress` (benchmarks/RESULTS.md gives the commands
// of the 645-sample set of windows of subject 16's clips).
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "bench_timing.hpp"
#include "mocapdb/store/database.hpp"
#include "mocapdb/synthesis/motion_model.hpp"
#include "mocapdb/workflow/load_model.hpp"

using namespace mocapdb;
using bench::Clock;
using bench::seconds_since;

namespace {

double cpu_seconds() {
    timespec ts{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

struct Step {
    const char* name;
    double wall = 1e300, cpu = 1e300;
};

template <class F>
void timed(Step& s, F fn) {
    const auto w = Clock::now();
    const double c = cpu_seconds();
    fn();
    s.cpu = std::min(s.cpu, cpu_seconds() - c);
    s.wall = std::min(s.wall, seconds_since(w));
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 4) {
        std::fprintf(stderr, "usage: bench_synthesis_load DB.h5 SET v1,v2,... [repeats=3] [refit=1]\n");
        return 2;
    }
    const std::string path = argv[1], name = argv[2];
    std::vector<double> values;
    std::stringstream in(argv[3]);
    for (std::string item; std::getline(in, item, ',');) values.push_back(std::atof(item.c_str()));
    const VecX c = Eigen::Map<const VecX>(values.data(), static_cast<Eigen::Index>(values.size()));
    const int repeats = argc > 4 ? std::max(1, std::atoi(argv[4])) : 3;
    const bool refit = argc > 5 ? std::atoi(argv[5]) != 0 : true;

    Step open{"open"}, set{"load_set"}, timing{"load_aligned_timing"}, model{"load_model"}, kernel{"load_kernel_fit"},
        skeleton_step{"load_skeleton"}, aligned{"load_aligned_full"}, workflow_load{"workflow_load_motion_model"},
        build{"build_model"}, first{"first_motion"}, total{"load_total"}, refit_build{"build_model_refit"};
    Eigen::Index samples = 0, frames = 0;
    bool stored = false;
    double precompute = 0.0;
    for (int r = 0; r < repeats; ++r) {
        const auto w0 = Clock::now();
        const double c0 = cpu_seconds();
        std::unique_ptr<Database> db;
        timed(open, [&] { db = std::make_unique<Database>(path); });
        MotionSet s;
        timed(set, [&] { s = db->load_set(name); });
        std::optional<AlignedTiming> a;
        timed(timing, [&] { a = db->load_aligned_timing(name); });
        std::optional<StoredModel> m;
        timed(model, [&] { m = db->load_model(name); });
        synthesis::SynthesisOptions options;
        timed(kernel, [&] { options.kernel_fit = db->load_kernel_fit(name); });
        std::optional<ClipRecord> record;
        std::shared_ptr<const Skeleton> skeleton;
        timed(skeleton_step, [&] {
            record = db->find_clip(s.samples.front().clip);
            skeleton = db->load_skeleton(record->skeleton);
        });
        std::unique_ptr<synthesis::MotionModel> mm;
        timed(build, [&] {
            // moved in, as workflow::load_motion_model does
            mm = std::make_unique<synthesis::MotionModel>(std::move(m->model), *a, s, skeleton, record->frame_rate, options);
        });
        total.wall = std::min(total.wall, seconds_since(w0));
        total.cpu = std::min(total.cpu, cpu_seconds() - c0);
        timed(aligned, [&] { bench::g_sink = static_cast<double>(db->load_aligned(name)->samples()); });
        // What `mocapdb synth` calls: the steps above plus the check of every sample's clip.
        std::unique_ptr<synthesis::MotionModel> loaded;
        timed(workflow_load, [&] { loaded = workflow::load_motion_model(*db, name); });
        bench::g_sink = static_cast<double>(loaded->samples());
        loaded.reset();  // its destruction not timed
        timed(first, [&] { frames = mm->motion_poses(c).cols(); });
        samples = mm->samples();
        stored = mm->report().kernel_precomputed;
        precompute = mm->report().precompute_seconds;
        if (refit && r == 0) {
            timed(refit_build, [&] {
                synthesis::MotionModel again(db->load_model(name)->model, *a, s, skeleton, record->frame_rate, {});
                bench::g_sink = again.report().model.range;
            });
        }
    }
    std::printf("samples %lld\nkernel_stored %d\nframes %lld\nprecompute_s %.4f\n", static_cast<long long>(samples),
                stored ? 1 : 0, static_cast<long long>(frames), precompute);
    for (const Step* st : {&open, &set, &timing, &model, &kernel, &skeleton_step, &build, &total, &first, &aligned, &workflow_load})
        std::printf("%s_wall_s %.4f\n%s_cpu_s %.4f\n", st->name, st->wall, st->name, st->cpu);
    if (refit) std::printf("%s_wall_s %.4f\n%s_cpu_s %.4f\n", refit_build.name, refit_build.wall, refit_build.name, refit_build.cpu);
    return 0;
}
