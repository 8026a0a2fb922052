// "Allocation-free per pose query after setup": heap allocations counted around single-pose queries
// (glibc: malloc is wrapped in this test executable; skipped in sanitized builds, whose allocator
// must not be replaced).
#include <catch2/catch.hpp>

#include <atomic>
#include <cstdlib>

#include "mocapdb/compression/dof_weights.hpp"
#include "mocapdb/dataset/alignment.hpp"
#include "mocapdb/io/clip_file.hpp"
#include "mocapdb/synthesis/motion_model.hpp"
#include "mocapdb/synthesis/naive_motion_model.hpp"
#include "shared_data.hpp"

#if defined(__GLIBC__) && !defined(MOCAPDB_SANITIZED_BUILD)
#define MOCAPDB_COUNT_MALLOC 1
namespace {
std::atomic<bool> g_counting{false};
std::atomic<long> g_allocations{0};
}  // namespace
extern "C" void* __libc_malloc(std::size_t size);
extern "C" void* malloc(std::size_t size) {
    if (g_counting.load(std::memory_order_relaxed)) g_allocations.fetch_add(1, std::memory_order_relaxed);
    return __libc_malloc(size);
}
#endif

using namespace mocapdb;
using namespace mocapdb::synthesis;

TEST_CASE("single pose queries do not allocate once the workspace is sized", "[synthesis][shared]") {
#ifndef MOCAPDB_COUNT_MALLOC
    WARN("SKIPPED: allocation counting needs glibc and an unsanitized build");
#else
    MOCAPDB_REQUIRE_SHARED(test::datasets_dir() / "cmu-asfamc");
    std::vector<Clip> clips;
    for (int t : {11, 13, 15, 17, 19, 21, 23})
        clips.push_back(read_clip(test::datasets_dir() / "cmu-asfamc" / ("16_" + std::to_string(t) + ".amc")));
    AlignOptions ao;
    ao.method = "linear";
    ao.frames = 12;
    const AlignedSet aligned = align_samples(clips, ao);
    MotionSet set;
    set.name = "walks";
    set.parameter_names = {"a", "b"};
    set.parameter_units = {"", ""};
    set.parameters.resize(aligned.samples(), 2);
    for (Eigen::Index i = 0; i < aligned.samples(); ++i) {
        set.parameters(i, 0) = std::sin(1.3 * static_cast<double>(i));
        set.parameters(i, 1) = std::cos(0.7 * static_cast<double>(i) + 0.2);
        set.samples.push_back({"c" + std::to_string(i), 0, clips[static_cast<std::size_t>(i)].frame_count()});
    }
    const VecX weight = compression::position_error_weights(*clips.front().skeleton);
    const compression::SetModel sm = compression::fit_set_model(aligned.tensor, weight, {12, 6, 5}, tensor::TuckerMethod::Hosvd);
    SynthesisOptions options;
    options.levels = {{6, 3, 3}};
    const MotionModel model(sm, aligned, set, clips.front().skeleton, 120.0, options);
    const NaiveMotionModel naive(aligned, set, clips.front().skeleton, 120.0, weight);
    {
        // The counter sees allocations (so the zero below means something).
        g_allocations = 0;
        g_counting = true;
        VecX probe = VecX::Constant(1000, 1.0);
        void* volatile raw = std::malloc(64);
        g_counting = false;
        std::free(raw);
        CHECK(g_allocations.load() >= 2);
        CHECK(probe.sum() == 1000.0);
    }
    for (const SynthesisModel* m : {static_cast<const SynthesisModel*>(&model), static_cast<const SynthesisModel*>(&naive)}) {
        Workspace ws;
        VecX out(m->dofs()), coef(m->coefficient_size()), c(2);
        c << 0.1, 0.2;
        for (Eigen::Index level = 0; level < m->levels(); ++level) m->pose(c, 1.5, out, ws, level);  // sizes the workspace
        g_allocations = 0;
        g_counting = true;
        for (int k = 0; k < 100; ++k) {
            c << 0.01 * k - 0.5, 0.3 - 0.004 * k;
            const double t = 0.1 * k;
            m->pose(c, t, out, ws, k % m->levels());
            m->coefficients(c, coef, ws);
            m->pose_from_coefficients(coef, t, out, ws, 0);
        }
        g_counting = false;
        INFO(m->kind() << ": " << g_allocations.load() << " allocations in 100 queries");
        CHECK(g_allocations.load() == 0);
        CHECK(out.allFinite());
    }
#endif
}
