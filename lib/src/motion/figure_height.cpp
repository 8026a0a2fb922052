#include "mocapdb/motion/figure_height.hpp"

#include <algorithm>
#include <cstdio>
#include <limits>
#include <vector>

#include "mocapdb/motion/forward_kinematics.hpp"

namespace mocapdb {

double figure_height(const Skeleton& skeleton, const double* row) {
    GlobalPose pose;
    forward_kinematics(skeleton, row, pose);
    double low = std::numeric_limits<double>::infinity();
    double high = -low;
    std::vector<bool> body(skeleton.size(), false);  // the motion root and everything below it
    for (std::size_t j = skeleton.motion_root(); j < skeleton.size(); ++j) {
        const int parent = skeleton.joint(j).parent;
        body[j] = j == skeleton.motion_root() || (parent >= 0 && body[static_cast<std::size_t>(parent)]);
        if (!body[j]) continue;
        low = std::min(low, pose.positions[j].y());
        high = std::max(high, pose.positions[j].y());
    }
    return high - low;
}

std::string figure_height_warning(double height_cm) {
    if (height_cm >= kPlausibleFigureMinCm && height_cm <= kPlausibleFigureMaxCm) return {};
    char text[320];
    std::snprintf(text, sizeof text,
                  "the figure is %.1f cm tall at frame 0 (lowest to highest joint), outside %.0f-%.0f cm: check "
                  "the file's length unit and, for BVH, whether position channels replace OFFSET "
                  "(the import's BVH position convention)",
                  height_cm, kPlausibleFigureMinCm, kPlausibleFigureMaxCm);
    return text;
}

}  // namespace mocapdb
