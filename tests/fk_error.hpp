#pragma once
// The FK bound of lossy clips, as tests check it: max distance (cm) between a source clip and its
// decode over every joint, end site and frame (header-only: every test executable links mocapdb).
#include <catch2/catch.hpp>

#include <algorithm>

#include "mocapdb/motion/clip.hpp"
#include "mocapdb/motion/forward_kinematics.hpp"

namespace mocapdb::test {

inline double max_position_error(const Clip& source, const Clip& decoded) {
    REQUIRE(decoded.frame_count() == source.frame_count());
    const MatX a = joint_positions(source);
    const MatX b = joint_positions(decoded);
    REQUIRE(a.rows() == b.rows());
    double worst = 0.0;
    for (Eigen::Index f = 0; f < a.cols(); ++f)
        for (Eigen::Index j = 0; j < a.rows(); j += 3)
            worst = std::max(worst, (a.block<3, 1>(j, f) - b.block<3, 1>(j, f)).norm());
    return worst;
}

}  // namespace mocapdb::test
