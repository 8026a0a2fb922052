#pragma once
// The stages of pack_group (internal to the packing module), in order: the group's layout (clip and
// skeleton entries), the dofs that vary, the bases (pass 0), the per-window step search (pass 1,
// window_search.cpp) and the entropy coding (pass 2). Each stage fills its part of the GroupModel.
// The clip passes run on PackRun's workers; what they sum is summed in clip or worker order, so the
// bytes do not depend on how clips were spread over threads.
#include <atomic>
#include <cstdint>
#include <mutex>
#include <vector>

#include "mocapdb/core/parallel_tasks.hpp"
#include "mocapdb/core/progress.hpp"
#include "mocapdb/packing/coefficient_coder.hpp"
#include "mocapdb/packing/error_stats.hpp"
#include "mocapdb/packing/packed_group.hpp"
#include "group_model.hpp"

namespace mocapdb::packing::detail {

/// The clips, options and workers of one pack_group call, and its progress (two units a window).
class PackRun {
public:
    PackRun(const std::vector<const Clip*>& clips, const PackOptions& options, const ProgressCallback& progress,
            std::uint64_t window_total);
    const std::vector<const Clip*>& clips;
    const PackOptions& options;
    const std::size_t threads;  ///< min(options.threads, clips)

    /// per_clip(i, states[t]) for every clip i, on states.size() workers; an exception on any worker
    /// reaches the caller (run_on_workers).
    template <class PerClip, class State>
    void run(PerClip&& per_clip, std::vector<State>& states) {
        run_on_workers(states.size(), clips.size(), [&](std::size_t i, std::size_t t) { per_clip(i, states[t]); });
    }
    /// Counts `windows` units done and reports progress at clip `c`.
    void done(const Clip& c, int windows);

private:
    const ProgressCallback& progress_;
    const std::uint64_t total_units_;
    std::atomic<std::uint64_t> units_done_{0};
    std::mutex mutex_;
};

/// Window `w` of x (D by F) as D by W, the last frame repeated past the end.
MatX window_of(const MatX& x, int w, int length);

/// Windows of `frames` frames, `window` frames each (the last one may be short).
inline std::uint64_t window_count(std::uint64_t frames, int window) {
    return (frames + static_cast<std::uint64_t>(window) - 1) / static_cast<std::uint64_t>(window);
}

/// The layout shared by the group (frame rate, W, dofs) and the per-clip entries: distinct skeletons
/// (float32-rounded, as the decoder will see them), canonicalizations, first windows. Returns the
/// group's window count.
std::uint64_t layout_group(const std::vector<const Clip*>& clips, int window, GroupModel& m);

/// Pre-pass: which dofs vary in the group (m.active); the others are stored as constants.
void find_active_dofs(PackRun& run, GroupModel& m);

/// Pass 0: the dof and time bases (learned: eigenvectors of the group's second moments, ST-HOSVD at
/// full rank; or the options' fixed ones), their energies and the scan.
void fit_bases(PackRun& run, GroupModel& m);

/// One window's quantization (pass 1).
struct WindowResult {
    std::uint8_t step = 0;
    std::vector<std::int32_t> q;  // scan order, trimmed after the last nonzero
    std::vector<double> raw;      // step == kRawStep: the window's source channel rows, row-major
};

/// What pass 1 measures besides the windows (per worker, then merged in worker order).
struct SearchTotals {
    explicit SearchTotals(double e) : errors(e) {}
    ErrorAccumulator errors;
    ContextCounts counts;
    std::size_t probes = 0;
    std::size_t raw_windows = 0;
};

/// Pass 1: per window, the coarsest step whose decode meets the bound (or the source rows, see
/// kRawStep); the context statistics, errors and counts merged into `totals`. PackingFailed when
/// even a window's source rows miss the bound.
std::vector<WindowResult> quantize_windows(PackRun& run, const GroupModel& m, std::uint64_t window_total,
                                           SearchTotals& totals);

}  // namespace mocapdb::packing::detail
