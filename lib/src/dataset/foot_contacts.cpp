#include "mocapdb/dataset/foot_contacts.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "mocapdb/core/error.hpp"
#include "mocapdb/motion/forward_kinematics.hpp"
#include "mocapdb/motion/pose_vector.hpp"

namespace mocapdb {
namespace {

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return s;
}

// First joint whose lower-case name starts with one of `sides` and contains `part`.
std::optional<std::string> find_foot(const Skeleton& s, std::initializer_list<const char*> sides, const char* part) {
    for (const Joint& j : s.joints()) {
        if (j.end_site) continue;
        const std::string n = lower(j.name);
        if (n.find(part) == std::string::npos) continue;
        for (const char* side : sides)
            if (n.rfind(side, 0) == 0) return j.name;
    }
    return std::nullopt;
}

}  // namespace

std::vector<std::string> default_feet(const Skeleton& s) {
    for (const char* part : {"toe", "foot"}) {
        const auto left = find_foot(s, {"left", "l"}, part);
        const auto right = find_foot(s, {"right", "r"}, part);
        if (left && right) return {*left, *right};
    }
    throw InvalidArgument("no left/right foot joints found by name (toe/foot); name the foot joints explicitly");
}

Eigen::Matrix<bool, Eigen::Dynamic, Eigen::Dynamic> foot_contacts(const Clip& clip, const FootContactOptions& options) {
    validate(clip);
    const Skeleton& s = *clip.skeleton;
    const std::vector<std::string> feet = options.feet.empty() ? default_feet(s) : options.feet;
    std::vector<std::size_t> index;
    for (const std::string& name : feet) {
        const auto j = s.find(name);
        if (!j) throw InvalidArgument("foot joint '" + name + "' is not in the skeleton");
        index.push_back(*j);
    }
    const MatX p = joint_positions(clip);
    const auto frames = p.cols();
    Eigen::Matrix<bool, Eigen::Dynamic, Eigen::Dynamic> contact(static_cast<Eigen::Index>(feet.size()), frames);
    for (std::size_t k = 0; k < index.size(); ++k) {
        const auto r = 3 * static_cast<Eigen::Index>(index[k]);
        std::vector<double> heights(static_cast<std::size_t>(frames));
        for (Eigen::Index f = 0; f < frames; ++f) heights[static_cast<std::size_t>(f)] = p(r + 1, f);
        std::vector<double> sorted = heights;
        const auto nth = sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 20);
        std::nth_element(sorted.begin(), nth, sorted.end());
        const double floor = sorted.empty() ? 0.0 : *nth;
        for (Eigen::Index f = 0; f < frames; ++f) {
            // Central difference of the horizontal position (one-sided at the ends).
            const Eigen::Index a = std::max<Eigen::Index>(f - 1, 0), b = std::min<Eigen::Index>(f + 1, frames - 1);
            double speed = 0.0;
            if (b > a) {
                const double dx = p(r, b) - p(r, a), dz = p(r + 2, b) - p(r + 2, a);
                speed = std::hypot(dx, dz) * clip.frame_rate / static_cast<double>(b - a);
            }
            contact(static_cast<Eigen::Index>(k), f) =
                heights[static_cast<std::size_t>(f)] - floor <= options.height_tolerance_cm &&
                speed <= options.speed_tolerance_cm_s;
        }
    }
    return contact;
}

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
