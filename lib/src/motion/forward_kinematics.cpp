#include "mocapdb/motion/forward_kinematics.hpp"

#include <string>

#include "mocapdb/core/error.hpp"

namespace mocapdb {

namespace {

// Forward kinematics over local transforms given by translation(j) and rotation(j): one composition
// for frame rows (channels) and for decoded local poses (rotations).
template <class Translation, class Rotation>
void compose(const Skeleton& skeleton, const Translation& translation, const Rotation& rotation, GlobalPose& out_pose) {
    const std::size_t n = skeleton.size();
    out_pose.positions.resize(n);
    out_pose.orientations.resize(n);
    for (std::size_t j = 0; j < n; ++j) {
        const int parent = skeleton.joint(j).parent;
        const Vec3 t = translation(j);
        const Quat r = rotation(j);
        if (parent < 0) {
            out_pose.positions[j] = t;
            out_pose.orientations[j] = r;
        } else {
            const Quat& parent_rotation = out_pose.orientations[static_cast<std::size_t>(parent)];
            out_pose.positions[j] = out_pose.positions[static_cast<std::size_t>(parent)] + parent_rotation * t;
            out_pose.orientations[j] = parent_rotation * r;
        }
    }
}

template <class Translation, class Rotation>
JointTransform compose_root(const Skeleton& skeleton, const Translation& translation, const Rotation& rotation) {
    JointTransform t;
    for (std::size_t j : skeleton.motion_root_chain()) {
        t.position += t.orientation * translation(j);
        t.orientation = t.orientation * rotation(j);
    }
    return t;
}

void check_local(const Skeleton& skeleton, const std::vector<Quat>& rotations, const std::vector<Vec3>& translations,
                 const char* where) {
    if (rotations.size() != skeleton.size() || translations.size() != skeleton.size())
        throw InvalidArgument(std::string(where) + ": expected " + std::to_string(skeleton.size()) +
                              " local transforms, got " + std::to_string(rotations.size()) + " rotations and " +
                              std::to_string(translations.size()) + " translations");
}

}  // namespace

void forward_kinematics(const Skeleton& skeleton, const double* row, GlobalPose& out_pose) {
    compose(
        skeleton, [&](std::size_t j) { return skeleton.local_translation(j, row); },
        [&](std::size_t j) { return skeleton.local_rotation(j, row); }, out_pose);
}

void forward_kinematics(const Skeleton& skeleton, const std::vector<Quat>& rotations,
                        const std::vector<Vec3>& translations, GlobalPose& out_pose) {
    check_local(skeleton, rotations, translations, "forward_kinematics");
    compose(
        skeleton, [&](std::size_t j) { return translations[j]; }, [&](std::size_t j) { return rotations[j]; },
        out_pose);
}

JointTransform motion_root_transform(const Skeleton& skeleton, const double* row) {
    return compose_root(
        skeleton, [&](std::size_t j) { return skeleton.local_translation(j, row); },
        [&](std::size_t j) { return skeleton.local_rotation(j, row); });
}

JointTransform local_root_transform(const Skeleton& skeleton, const std::vector<Quat>& rotations,
                                    const std::vector<Vec3>& translations) {
    check_local(skeleton, rotations, translations, "local_root_transform");
    return compose_root(
        skeleton, [&](std::size_t j) { return translations[j]; }, [&](std::size_t j) { return rotations[j]; });
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
