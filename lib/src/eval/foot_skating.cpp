#include "mocapdb/eval/foot_skating.hpp"

#include <cmath>

#include "mocapdb/core/error.hpp"
#include "mocapdb/motion/forward_kinematics.hpp"

namespace mocapdb::eval {

FootSkating foot_skating(const Clip& clip, const FootContactOptions& options) {
    if (clip.frame_count() < 2) throw InvalidArgument("foot_skating: the clip needs at least 2 frames");
    FootContactOptions o = options;
    if (o.feet.empty()) o.feet = default_feet(*clip.skeleton);
    const auto contacts = foot_contacts(clip, o);
    const MatX p = joint_positions(clip);
    FootSkating out;
    const Eigen::Index frames = p.cols();
    long long in_contact = 0;
    long long pairs = 0;
    for (std::size_t k = 0; k < o.feet.size(); ++k) {
        const auto j = clip.skeleton->find(o.feet[k]);
        if (!j) throw InvalidArgument("foot_skating: no joint '" + o.feet[k] + "' in the skeleton");
        const Eigen::Index r = static_cast<Eigen::Index>(3 * *j);
        const Eigen::Index row = static_cast<Eigen::Index>(k);
        for (Eigen::Index f = 0; f < frames; ++f) {
            if (contacts(row, f)) ++in_contact;
            if (f + 1 < frames && contacts(row, f) && contacts(row, f + 1)) {
                ++pairs;
                const double dx = p(r, f + 1) - p(r, f);
                const double dz = p(r + 2, f + 1) - p(r + 2, f);
                out.travel_cm += std::sqrt(dx * dx + dz * dz);
            }
        }
    }
    out.contact_seconds = static_cast<double>(pairs) / clip.frame_rate;
    out.cm_per_s = out.contact_seconds > 0.0 ? out.travel_cm / out.contact_seconds : 0.0;
    out.contact_fraction =
        static_cast<double>(in_contact) / static_cast<double>(frames * static_cast<Eigen::Index>(o.feet.size()));
    return out;
}

}  // namespace mocapdb::eval
