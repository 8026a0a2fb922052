#include "mocapdb/dataset/gait_phase.hpp"

#include <algorithm>
#include <cmath>

#include "mocapdb/core/error.hpp"
#include "mocapdb/dataset/foot_contacts.hpp"
#include "mocapdb/motion/forward_kinematics.hpp"

namespace mocapdb {

VecX forward_foot_separation(const Clip& clip, const std::vector<std::string>& feet_in) {
    validate(clip);
    const Skeleton& s = *clip.skeleton;
    const std::vector<std::string> feet = feet_in.empty() ? default_feet(s) : feet_in;
    if (feet.size() != 2) throw InvalidArgument("gait phase: give two feet (left, right)");
    std::size_t index[2];
    for (int k = 0; k < 2; ++k) {
        const auto j = s.find(feet[static_cast<std::size_t>(k)]);
        if (!j) throw InvalidArgument("foot joint '" + feet[static_cast<std::size_t>(k)] + "' is not in the skeleton");
        index[k] = *j;
    }
    const MatX p = joint_positions(clip);
    const VecX heading = root_headings(clip);
    const Vec3& rest = s.forward();
    VecX out(p.cols());
    for (Eigen::Index f = 0; f < p.cols(); ++f) {
        // The rest forward direction turned by the heading about +Y.
        const double c = std::cos(heading[f]), sn = std::sin(heading[f]);
        const Vec3 forward(c * rest.x() + sn * rest.z(), 0.0, -sn * rest.x() + c * rest.z());
        const Vec3 apart = p.block<3, 1>(3 * static_cast<Eigen::Index>(index[0]), f) -
                           p.block<3, 1>(3 * static_cast<Eigen::Index>(index[1]), f);
        out[f] = apart.dot(forward.normalized());
    }
    return out;
}

std::vector<std::size_t> left_foot_passes(const VecX& separation, double min_swing_cm) {
    std::vector<std::size_t> passes;
    if (separation.size() < 3) return passes;
    std::vector<double> magnitude(static_cast<std::size_t>(separation.size()));
    for (Eigen::Index f = 0; f < separation.size(); ++f)
        magnitude[static_cast<std::size_t>(f)] = std::abs(separation[f]);
    const auto p90 = magnitude.begin() + static_cast<std::ptrdiff_t>(magnitude.size() * 9 / 10);
    std::nth_element(magnitude.begin(), p90, magnitude.end());
    if (!(*p90 > min_swing_cm)) return passes;
    const double threshold = std::max(min_swing_cm, 0.3 * *p90);
    bool was_behind = false;   // been below -threshold since the last pass
    std::size_t crossing = 0;  // last frame where the separation became >= 0
    bool have_crossing = false;
    for (Eigen::Index f = 1; f < separation.size(); ++f) {
        const double d = separation[f];
        if (separation[f - 1] < 0.0 && d >= 0.0) {
            crossing = static_cast<std::size_t>(f);
            have_crossing = true;
        }
        if (d < -threshold) {
            was_behind = true;
            have_crossing = false;
        } else if (d > threshold && was_behind && have_crossing) {
            passes.push_back(crossing);
            was_behind = false;
        }
    }
    if (passes.empty()) return passes;
    // Passes at the clip's ends, which the hysteresis cannot confirm: the first frame just after one
    // (lead >= 0 but less than one frame's rise) and a last crossing the clip ends before confirming,
    // each only when the lead grows there at least half as fast as at the confirmed passes (feet
    // that come to rest side by side jitter around 0 without a pass).
    std::vector<double> rates;
    for (std::size_t p : passes)
        rates.push_back(separation[static_cast<Eigen::Index>(p)] - separation[static_cast<Eigen::Index>(p) - 1]);
    std::nth_element(rates.begin(), rates.begin() + static_cast<std::ptrdiff_t>(rates.size() / 2), rates.end());
    const double typical_rate = rates[rates.size() / 2];
    const double first_rise = separation[1] - separation[0];
    if (separation[0] >= 0.0 && first_rise > separation[0] && first_rise >= 0.5 * typical_rate && passes.front() > 0)
        passes.insert(passes.begin(), 0);
    const auto last = static_cast<std::size_t>(separation.size() - 1);
    if (was_behind && have_crossing && crossing > passes.back()) {
        const double rate =
            crossing == last
                ? separation[static_cast<Eigen::Index>(last)] - separation[static_cast<Eigen::Index>(last) - 1]
                : (separation[static_cast<Eigen::Index>(last)] - separation[static_cast<Eigen::Index>(crossing)]) /
                      static_cast<double>(last - crossing);
        if (rate >= 0.5 * typical_rate) passes.push_back(crossing);
    }
    return passes;
}

}  // namespace mocapdb
