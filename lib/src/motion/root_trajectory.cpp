#include "mocapdb/motion/root_trajectory.hpp"

#include <cmath>

#include "mocapdb/motion/forward_kinematics.hpp"
#include "mocapdb/motion/pose_vector.hpp"

namespace mocapdb {

MatX root_positions(const Clip& clip) {
    validate(clip);
    MatX out(3, static_cast<Eigen::Index>(clip.frame_count()));
    for (std::size_t f = 0; f < clip.frame_count(); ++f)
        out.col(static_cast<Eigen::Index>(f)) = motion_root_transform(*clip.skeleton, clip.frame(f)).position;
    return out;
}

VecX root_headings(const Clip& clip) {
    validate(clip);
    const Skeleton& s = *clip.skeleton;
    VecX out(static_cast<Eigen::Index>(clip.frame_count()));
    double previous = 0.0;
    for (std::size_t f = 0; f < clip.frame_count(); ++f) {
        double h = heading_of(motion_root_transform(s, clip.frame(f)).orientation, s.forward());
        if (f > 0) h -= 2.0 * kPi * std::round((h - previous) / (2.0 * kPi));
        out[static_cast<Eigen::Index>(f)] = previous = h;
    }
    return out;
}

}  // namespace mocapdb
