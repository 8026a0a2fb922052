#include "mocapdb/dataset/travel_frame.hpp"

#include <cmath>

#include "mocapdb/motion/forward_kinematics.hpp"

namespace mocapdb {

TravelFrame travel_canonicalization(const Clip& sample, const TravelFrameOptions& options) {
    TravelFrame out;
    out.canonical = canonicalization_of(sample);  // validates; translation and the fallback heading
    if (sample.frame_count() < 2) return out;
    const Vec3 p0 = motion_root_transform(*sample.skeleton, sample.frame(0)).position;
    double dx = 0.0, dz = 0.0;
    for (std::size_t f = 1; f < sample.frame_count(); ++f) {
        const Vec3 p = motion_root_transform(*sample.skeleton, sample.frame(f)).position;
        dx = p.x() - p0.x();
        dz = p.z() - p0.z();
        if (std::hypot(dx, dz) >= options.distance_cm) break;
    }
    out.travel_cm = std::hypot(dx, dz);
    if (!(out.travel_cm >= options.min_travel_cm)) return out;
    // R_y(yaw) takes +Z to (sin yaw, 0, cos yaw): the travel direction maps back onto +Z.
    out.canonical.yaw = std::atan2(dx, dz);
    out.by_travel = true;
    return out;
}

}  // namespace mocapdb
