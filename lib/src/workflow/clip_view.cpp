#include "mocapdb/workflow/clip_view.hpp"

#include <algorithm>
#include <cmath>

#include "mocapdb/core/error.hpp"
#include "mocapdb/motion/forward_kinematics.hpp"
#include "mocapdb/packing/group_decoder.hpp"
#include "mocapdb/packing/measured_pack.hpp"
#include "mocapdb/store/database.hpp"

namespace mocapdb::workflow {

RigView rig_view(const Skeleton& skeleton) {
    RigView rig;
    for (const Joint& j : skeleton.joints()) {
        rig.names.push_back(j.name);
        rig.parents.push_back(j.parent);
        rig.end_sites.push_back(j.end_site);
    }
    return rig;
}

namespace {

/// Frames [begin, end) of the output, metadata and room for the positions (no FK yet).
ClipPositions empty_positions(const Clip& clip, std::size_t begin, std::size_t end) {
    ClipPositions out;
    out.rig = rig_view(*clip.skeleton);
    out.frame_rate = clip.frame_rate;
    out.begin = begin;
    out.frames = end - begin;
    out.positions.resize(out.frames * clip.skeleton->size() * 3);
    return out;
}

/// Frame `row` of `p` from an FK pose.
void store_pose(ClipPositions& p, std::size_t row, const GlobalPose& pose) {
    float* dst = p.positions.data() + row * pose.positions.size() * 3;
    for (std::size_t j = 0; j < pose.positions.size(); ++j)
        for (int k = 0; k < 3; ++k) dst[3 * j + static_cast<std::size_t>(k)] = static_cast<float>(pose.positions[j](k));
}

}  // namespace

ClipPositions clip_positions(const Clip& clip, std::size_t begin, std::size_t end) {
    const std::size_t frames = clip.frame_count();
    if (begin >= frames)
        throw InvalidArgument("first frame " + std::to_string(begin) + " is beyond the clip's " +
                              std::to_string(frames) + " frames");
    end = std::min(end, frames);
    ClipPositions out = empty_positions(clip, begin, end);
    GlobalPose pose;
    for (std::size_t f = begin; f < end; ++f) {
        forward_kinematics(*clip.skeleton, clip.frame(f), pose);
        store_pose(out, f - begin, pose);
    }
    return out;
}

namespace {

PackedComparison compare(const Clip& source, const Clip& packed, std::size_t begin, std::size_t end) {
    PackedComparison out;
    out.source = empty_positions(source, begin, end);
    out.packed = empty_positions(packed, begin, end);
    // One FK pass per clip gives the positions shown and the distances (in double, not from the
    // float32 copies).
    const Skeleton& ss = *source.skeleton;
    const Skeleton& ps = *packed.skeleton;
    const std::size_t joints = ss.size();
    out.errors.resize(out.source.frames * joints);
    GlobalPose a, b;
    double sum_sq = 0.0;
    for (std::size_t f = begin; f < end; ++f) {
        forward_kinematics(ss, source.frame(f), a);
        forward_kinematics(ps, packed.frame(f - begin), b);
        store_pose(out.source, f - begin, a);
        store_pose(out.packed, f - begin, b);
        for (std::size_t j = 0; j < joints; ++j) {
            const double d = (a.positions[j] - b.positions[j]).norm();
            out.errors[(f - begin) * joints + j] = static_cast<float>(d);
            sum_sq += d * d;
            if (d > out.max_cm) {
                out.max_cm = d;
                out.worst_frame = f;
                out.worst_joint = ss.joint(j).name;
            }
        }
    }
    out.rmse_cm = std::sqrt(sum_sq / static_cast<double>(std::max<std::size_t>(out.errors.size(), 1)));
    return out;
}

std::size_t checked_end(const Clip& source, const std::string& clip, std::size_t begin, std::size_t end) {
    if (begin >= source.frame_count())
        throw InvalidArgument("clip '" + clip + "': first frame " + std::to_string(begin) + " is beyond its " +
                              std::to_string(source.frame_count()) + " frames");
    return std::min(end, source.frame_count());
}

}  // namespace

PackedComparison compare_with_packed(const Database& db, const std::string& clip, std::size_t begin, std::size_t end) {
    const Clip source = db.load_clip(clip);
    end = checked_end(source, clip, begin, end);
    PackedComparison out = compare(source, db.load_clip_packed(clip, begin, end), begin, end);
    out.tier_max_error_cm = db.packed()->max_error_cm;  // load_clip_packed threw if there is no tier
    return out;
}

PackedComparison compare_with_packed_at(const Clip& source, double max_error_cm, std::size_t begin, std::size_t end) {
    if (!(max_error_cm > 0.0) || !std::isfinite(max_error_cm))
        throw InvalidArgument("max error " + std::to_string(max_error_cm) + " cm: expected a positive finite number");
    end = checked_end(source, source.name, begin, end);
    packing::PackOptions options;
    options.max_error_cm = max_error_cm;
    const packing::MeasuredGroup group = packing::pack_measured({&source}, options);
    const Clip packed = slice(packing::GroupDecoder(group.packed.bytes).decode_clip(0), begin, end);
    PackedComparison out = compare(source, packed, begin, end);
    out.tier_max_error_cm = max_error_cm;
    return out;
}

}  // namespace mocapdb::workflow
