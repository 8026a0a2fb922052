#include "mocapdb/dataset/unwarp.hpp"

#include <algorithm>

#include "mocapdb/core/error.hpp"

namespace mocapdb {

MatX poses_at_sample_frames(const Eigen::Ref<const MatX>& aligned, const Eigen::Ref<const VecX>& warp,
                            Eigen::Index frames) {
    const Eigen::Index t_count = aligned.cols();
    if (warp.size() != t_count || t_count < 1)
        throw InvalidArgument("poses_at_sample_frames: " + std::to_string(t_count) + " aligned frames but " +
                              std::to_string(warp.size()) + " warp values");
    if (frames < 1) throw InvalidArgument("poses_at_sample_frames: at least one output frame is needed");
    for (Eigen::Index t = 1; t < t_count; ++t)
        if (!(warp[t] > warp[t - 1]))
            throw InvalidArgument("poses_at_sample_frames: the warp must increase strictly (aligned frame " +
                                  std::to_string(t) + ")");
    MatX out(aligned.rows(), frames);
    Eigen::Index t = 0;  // aligned segment [t, t + 1] holding the current frame; frames only move forward
    for (Eigen::Index f = 0; f < frames; ++f) {
        const double x = static_cast<double>(f);
        if (t_count == 1 || x <= warp[0]) {
            out.col(f) = aligned.col(0);
            continue;
        }
        if (x >= warp[t_count - 1]) {
            out.col(f) = aligned.col(t_count - 1);
            continue;
        }
        while (warp[t + 1] < x) ++t;
        const double a = (x - warp[t]) / (warp[t + 1] - warp[t]);
        out.col(f) = (1.0 - a) * aligned.col(t) + a * aligned.col(t + 1);
    }
    return out;
}

Clip clip_from_pose_vectors(std::shared_ptr<const Skeleton> skeleton, const Eigen::Ref<const MatX>& poses,
                            const Canonicalization& canonical, double frame_rate, std::string name) {
    Clip clip;
    clip.channels = from_pose_vectors(*skeleton, poses, canonical);
    clip.skeleton = std::move(skeleton);
    clip.frame_rate = frame_rate;
    clip.name = std::move(name);
    validate(clip);
    return clip;
}

}  // namespace mocapdb
