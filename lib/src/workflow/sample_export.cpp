#include "mocapdb/workflow/sample_export.hpp"

#include "mocapdb/core/error.hpp"
#include "mocapdb/dataset/unwarp.hpp"

namespace mocapdb::workflow {

Clip sample_at_own_timing(const AlignedSetData& data, const Tensor3& poses, Eigen::Index n, const std::string& name) {
    if (n < 0 || n >= poses.dimension(2) || n >= data.aligned.samples())
        throw InvalidArgument("sample " + std::to_string(n) + " of a set of " + std::to_string(data.aligned.samples()));
    if (poses.dimension(0) != data.aligned.tensor.dimension(0) ||
        poses.dimension(1) != data.aligned.tensor.dimension(1))
        throw InvalidArgument("poses of another shape than the set's aligned tensor");
    const Eigen::Index d = poses.dimension(0), t = poses.dimension(1);
    const Eigen::Map<const MatX> aligned(poses.data() + n * d * t, d, t);
    const SampleRef& ref = data.set.samples[static_cast<std::size_t>(n)];
    const MatX own =
        poses_at_sample_frames(aligned, data.aligned.warps.col(n), static_cast<Eigen::Index>(ref.frame_count()));
    return clip_from_pose_vectors(data.skeleton, own, data.aligned.canonical[static_cast<std::size_t>(n)],
                                  data.frame_rate, name);
}

}  // namespace mocapdb::workflow
