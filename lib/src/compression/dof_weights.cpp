#include "mocapdb/compression/dof_weights.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "mocapdb/motion/pose_vector.hpp"

namespace mocapdb::compression {

VecX position_error_weights(const Skeleton& skeleton) {
    const std::size_t joints = skeleton.size();
    const PoseLayout layout(skeleton);

    // Longest bone path from each joint down to any joint below it (parents precede children, so
    // one backward pass suffices).
    std::vector<double> lever(joints, 0.0);
    for (std::size_t j = joints; j-- > 1;) {
        const auto parent = static_cast<std::size_t>(skeleton.joint(j).parent);
        lever[parent] = std::max(lever[parent], lever[j] + skeleton.joint(j).offset.norm());
    }
    // Terms on each joint's chain: the root translation plus every rotation joint strictly above it.
    std::vector<int> terms(joints, 1);
    int most_terms = 1;
    for (std::size_t j = 1; j < joints; ++j) {
        const auto parent = static_cast<std::size_t>(skeleton.joint(j).parent);
        terms[j] = terms[parent] + (layout.exp_map_row(parent) >= 0 ? 1 : 0);
        most_terms = std::max(most_terms, terms[j]);
    }

    const double k = most_terms;
    VecX w(static_cast<Eigen::Index>(layout.dof_count()));
    w.head<3>().setConstant(k * std::sqrt(3.0));
    for (std::size_t j : layout.rotation_joints()) {
        const double c = j == skeleton.motion_root() ? 1.0 + std::sqrt(2.0) : std::sqrt(3.0);
        w.segment<3>(layout.exp_map_row(j)).setConstant(k * c * std::max(lever[j], 1.0));
    }
    return w;
}

}  // namespace mocapdb::compression
