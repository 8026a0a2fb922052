#pragma once
// Measurements shared by the procedural tests: FK through the library (not the generators' own),
// per-frame continuity, and foot slide during the contacts the project's detector finds.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "mocapdb/dataset/foot_contacts.hpp"
#include "mocapdb/motion/forward_kinematics.hpp"
#include "mocapdb/motion/rotation.hpp"

namespace mocapdb::test {

/// World position of joint `name` at every frame (library FK).
inline std::vector<Vec3> joint_track(const Clip& clip, const std::string& name) {
    const auto j = clip.skeleton->find(name);
    if (!j) throw std::runtime_error("no joint " + name);
    GlobalPose pose;
    std::vector<Vec3> out;
    for (std::size_t f = 0; f < clip.frame_count(); ++f) {
        forward_kinematics(*clip.skeleton, clip.frame(f), pose);
        out.push_back(pose.positions[*j]);
    }
    return out;
}

struct Continuity {
    double max_rotation_step_deg = 0.0;  ///< largest change of any joint's local rotation between frames
    double max_channel_step_deg = 0.0;   ///< largest change of any rotation channel between frames
    double max_root_step_cm = 0.0;       ///< largest root displacement between frames
};

inline Continuity continuity(const Clip& clip) {
    const Skeleton& s = *clip.skeleton;
    Continuity c;
    for (std::size_t f = 1; f < clip.frame_count(); ++f) {
        for (std::size_t j = 0; j < s.size(); ++j) {
            if (!s.has_rotation(j)) continue;
            const double a = angle_between(s.local_rotation(j, clip.frame(f - 1)), s.local_rotation(j, clip.frame(f)));
            c.max_rotation_step_deg = std::max(c.max_rotation_step_deg, a * 180.0 / kPi);
            for (const ChannelType t : s.joint(j).channels) {
                if (!is_rotation(t)) continue;
                const int col = s.channel_column(j, t);
                c.max_channel_step_deg =
                    std::max(c.max_channel_step_deg, std::abs(clip.frame(f)[col] - clip.frame(f - 1)[col]) * 180.0 / kPi);
            }
        }
        c.max_root_step_cm = std::max(c.max_root_step_cm, (s.local_translation(0, clip.frame(f)) -
                                                           s.local_translation(0, clip.frame(f - 1))).norm());
    }
    return c;
}

/// Largest horizontal distance a foot joint moves away from where a detected contact began, over
/// every contact run of every foot (cm); `runs` counts the contact runs.
inline double max_contact_slide(const Clip& clip, const FootContactOptions& options, std::size_t* runs = nullptr) {
    const auto contacts = foot_contacts(clip, options);
    double worst = 0.0;
    std::size_t count = 0;
    for (Eigen::Index k = 0; k < contacts.rows(); ++k) {
        const auto track = joint_track(clip, options.feet[static_cast<std::size_t>(k)]);
        Eigen::Index start = -1;
        for (Eigen::Index f = 0; f < contacts.cols(); ++f) {
            if (!contacts(k, f)) {
                start = -1;
                continue;
            }
            if (start < 0) start = f, ++count;
            const Vec3 d = track[static_cast<std::size_t>(f)] - track[static_cast<std::size_t>(start)];
            worst = std::max(worst, std::hypot(d.x(), d.z()));
        }
    }
    if (runs) *runs = count;
    return worst;
}

}  // namespace mocapdb::test
