#include "mocapdb/motion/forward_kinematics.hpp"

namespace mocapdb {

void forward_kinematics(const Skeleton& skeleton, const double* row, GlobalPose& out_pose) {
    const std::size_t n = skeleton.size();
    out_pose.positions.resize(n);
    out_pose.orientations.resize(n);
    for (std::size_t j = 0; j < n; ++j) {
        const int parent = skeleton.joint(j).parent;
        const Vec3 translation = skeleton.local_translation(j, row);
        const Quat rotation = skeleton.local_rotation(j, row);
        if (parent < 0) {
            out_pose.positions[j] = translation;
            out_pose.orientations[j] = rotation;
        } else {
            const Quat& parent_rotation = out_pose.orientations[static_cast<std::size_t>(parent)];
            out_pose.positions[j] = out_pose.positions[static_cast<std::size_t>(parent)] + parent_rotation * translation;
            out_pose.orientations[j] = parent_rotation * rotation;
        }
    }
}

JointTransform motion_root_transform(const Skeleton& skeleton, const double* row) {
    JointTransform t;
    for (std::size_t j : skeleton.motion_root_chain()) {
        t.position += t.orientation * skeleton.local_translation(j, row);
        t.orientation = t.orientation * skeleton.local_rotation(j, row);
    }
    return t;
}

MatX joint_positions(const Clip& clip) {
    const Skeleton& skeleton = *clip.skeleton;
    const auto frames = static_cast<Eigen::Index>(clip.frame_count());
    MatX out(3 * static_cast<Eigen::Index>(skeleton.size()), frames);
    GlobalPose pose;
    for (Eigen::Index f = 0; f < frames; ++f) {
        forward_kinematics(skeleton, clip.frame(static_cast<std::size_t>(f)), pose);
        for (std::size_t j = 0; j < skeleton.size(); ++j)
            out.block<3, 1>(3 * static_cast<Eigen::Index>(j), f) = pose.positions[j];
    }
    return out;
}

}  // namespace mocapdb
