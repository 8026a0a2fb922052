#include "mocapdb/packing/runtime_encoder.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include "group_model.hpp"
#include "runtime_pose_plan.hpp"
#include "runtime_transform.hpp"
#include "runtime_encoder_body.hpp"
#include "runtime_writer.hpp"

namespace mocapdb::packing {

namespace {

/// Keys' step offset and directory levels of window W: the measured best (W 8: 4 and 1, W 16: 8 and 2).
int rt_key_offset_of(int W) { return W <= 8 ? 4 : 8; }
int rt_directory_levels_of(int W) {
    int levels = 0;
    while ((1 << levels) < W) ++levels;
    return std::max(0, levels - 2);
}

RuntimeBody rt_encode_at(const detail::GroupModel& m, const detail::RuntimePosePlan& plan,
                         const std::vector<const Clip*>& clips, const RuntimeOptions& o, int W,
                         const detail::ClipDone& clip_done) {
    const int key_offset = rt_key_offset_of(W), stored = rt_directory_levels_of(W);
    const detail::RuntimeCoefficients r =
        detail::runtime_transform(m, plan, clips, o.max_error_cm, W, key_offset, o.rounding, o.threads, clip_done);
    detail::RuntimeBodyParts parts;
    RuntimeBody out;
    out.bytes = detail::write_runtime_body(r, static_cast<int>(m.active.size()), stored, &parts);
    RuntimeStats& s = out.stats;
    s.bytes = out.bytes.size();
    s.header_bytes = parts.header;
    s.side_bytes = parts.side;
    s.offset_bytes = parts.offsets;
    s.entry_bytes = parts.entries;
    s.slack_bytes = parts.slack;
    s.window = W;
    s.key_offset = key_offset;
    s.directory_levels = stored;
    s.max_error_cm = r.max_error_cm;
    s.clips = clips.size();
    for (const Clip* c : clips) s.frames += c->frame_count();
    return out;
}

}  // namespace

namespace detail {

RuntimeBody encode_runtime_body(const GroupModel& m, const std::vector<const Clip*>& clips, const RuntimeOptions& o,
                                const std::function<void(std::size_t, int)>& clip_done) {
    // The encoder checks with the portable kernels; the AVX2 ones give the same bits.
    RuntimePosePlan plan;
    make_runtime_pose_plan(m, false, plan);
    const int passes = o.window != 0 ? 1 : 2;
    ClipDone done;
    if (clip_done) done = [&](std::size_t i) { clip_done(i, passes); };
    if (o.window != 0) return rt_encode_at(m, plan, clips, o, o.window, done);
    RuntimeBody w16 = rt_encode_at(m, plan, clips, o, 16, done);
    RuntimeBody w8 = rt_encode_at(m, plan, clips, o, 8, done);
    return static_cast<double>(w8.stats.bytes) <= 1.025 * static_cast<double>(w16.stats.bytes) ? std::move(w8)
                                                                                               : std::move(w16);
}

}  // namespace detail

RuntimeBody encode_runtime(const std::vector<std::uint8_t>& group, const std::vector<const Clip*>& clips,
                           const RuntimeOptions& o) {
    const auto t0 = std::chrono::steady_clock::now();
    if (!(o.max_error_cm > 0.0) || !std::isfinite(o.max_error_cm))
        throw InvalidArgument("encode_runtime: max_error_cm " + std::to_string(o.max_error_cm) +
                              ", expected > 0 and finite");
    if (o.window != 0 && o.window != 8 && o.window != 16)
        throw InvalidArgument("encode_runtime: window " + std::to_string(o.window) + ", expected 0 (choose), 8 or 16");
    if (!(o.rounding >= 0.1 && o.rounding <= 0.5))
        throw InvalidArgument("encode_runtime: rounding " + std::to_string(o.rounding) + ", expected 0.1 to 0.5");
    if (o.threads < 1)
        throw InvalidArgument("encode_runtime: threads " + std::to_string(o.threads) + ", expected >= 1");
    detail::GroupModel m;
    m.read_header(group.data(), group.size());
    if (m.runtime) throw InvalidArgument("encode_runtime: the group is a runtime group already (it holds its body)");
    if (clips.size() != m.clips.size())
        throw InvalidArgument("encode_runtime: " + std::to_string(clips.size()) + " clips, the packed group has " +
                              std::to_string(m.clips.size()));
    for (std::size_t i = 0; i < clips.size(); ++i) {
        const Clip& c = *clips[i];
        const detail::ClipEntry& e = m.clips[i];
        if (!c.skeleton || c.frame_count() != e.frames ||
            !detail::same_topology(*c.skeleton, *m.skeletons[e.skeleton].skeleton))
            throw InvalidArgument("encode_runtime: clip " + std::to_string(i) +
                                  (c.name.empty() ? "" : " (" + c.name + ")") + " is not the packed group's clip " +
                                  std::to_string(i) + " (" + std::to_string(c.frame_count()) + " frames, expected " +
                                  std::to_string(e.frames) + ", or another topology)");
    }
    RuntimeBody out = detail::encode_runtime_body(m, clips, o);
    out.stats.encode_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return out;
}

}  // namespace mocapdb::packing
