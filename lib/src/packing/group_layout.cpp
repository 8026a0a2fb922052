// pack_group's layout stage and pre-pass (pack_stages.hpp), and the runner its passes share.
#include <algorithm>

#include "mocapdb/core/float32.hpp"
#include "pack_stages.hpp"

namespace mocapdb::packing::detail {

PackRun::PackRun(const std::vector<const Clip*>& c, const PackOptions& o, const ProgressCallback& progress,
                 std::uint64_t window_total)
    : clips(c),
      options(o),
      threads(static_cast<std::size_t>(std::min<std::size_t>(static_cast<std::size_t>(o.threads), c.size()))),
      progress_(progress),
      total_units_(static_cast<std::uint64_t>(2 * window_total)) {}

void PackRun::done(const Clip& c, int windows) {
    units_done_ += static_cast<std::uint64_t>(windows);
    if (!progress_) return;
    std::lock_guard<std::mutex> lock(mutex_);
    progress_(Progress{units_done_.load(), total_units_, c.name});
}

MatX window_of(const MatX& x, int w, int length) {
    MatX out(x.rows(), length);
    const Eigen::Index f0 = static_cast<Eigen::Index>(w) * length;
    for (int t = 0; t < length; ++t) out.col(t) = x.col(std::min(f0 + t, x.cols() - 1));
    return out;
}

std::uint64_t layout_group(const std::vector<const Clip*>& clips, int window, GroupModel& m) {
    const Skeleton& s0 = *clips.front()->skeleton;
    m.frame_rate = clips.front()->frame_rate;
    m.window = window;
    m.pose_dofs = static_cast<int>(PoseLayout(s0).dof_count());
    m.extra_columns = extra_position_columns(s0);
    m.dofs = m.pose_dofs + static_cast<int>(m.extra_columns.size());

    std::vector<const Skeleton*> sources;
    m.clips.resize(clips.size());
    std::uint64_t window_total = 0;
    for (std::size_t i = 0; i < clips.size(); ++i) {
        const Skeleton& s = *clips[i]->skeleton;
        std::size_t k = 0;
        while (k < sources.size() && !(sources[k] == &s || sources[k]->same_structure(s, 0.0))) ++k;
        if (k == sources.size()) {
            sources.push_back(&s);
            m.skeletons.push_back(make_entry(s, m.pose_dofs, m.extra_columns.size()));
        }
        ClipEntry& e = m.clips[i];
        e.skeleton = static_cast<std::uint32_t>(k);
        e.frames = clips[i]->frame_count();
        const Canonicalization c = canonicalization_of(*clips[i]);
        Canonicalization rounded;
        rounded.translation = Vec3(float32_value(c.translation.x()), 0.0, float32_value(c.translation.z()));
        rounded.yaw = float32_value(c.yaw);
        e.set_canonical(rounded);
        e.first_window = window_total;
        window_total += window_count(e.frames, window);
    }
    return window_total;
}

void find_active_dofs(PackRun& run, GroupModel& m) {
    struct Range {
        VecX lo, hi;
    };
    std::vector<Range> ranges(run.threads, Range{VecX::Constant(m.dofs, 1e300), VecX::Constant(m.dofs, -1e300)});
    run.run(
        [&](std::size_t i, Range& r) {
            const MatX x = m.dofs_of(*run.clips[i], m.clips[i].canonical);
            r.lo = r.lo.cwiseMin(x.rowwise().minCoeff());
            r.hi = r.hi.cwiseMax(x.rowwise().maxCoeff());
        },
        ranges);
    for (std::size_t t = 1; t < run.threads; ++t) {
        ranges[0].lo = ranges[0].lo.cwiseMin(ranges[t].lo);
        ranges[0].hi = ranges[0].hi.cwiseMax(ranges[t].hi);
    }
    m.constant.assign(static_cast<std::size_t>(m.dofs), 0.0);
    for (int d = 0; d < m.dofs; ++d) {
        if (ranges[0].hi[d] - ranges[0].lo[d] > kConstantTolerance) m.active.push_back(d);
        else m.constant[static_cast<std::size_t>(d)] = 0.5 * (ranges[0].hi[d] + ranges[0].lo[d]);
    }
    m.fold_constant_joints();
}

}  // namespace mocapdb::packing::detail
