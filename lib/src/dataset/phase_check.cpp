#include "mocapdb/dataset/phase_check.hpp"

#include <algorithm>
#include <cmath>

#include "mocapdb/core/error.hpp"
#include "mocapdb/dataset/foot_contacts.hpp"
#include "mocapdb/dataset/gait_phase.hpp"

namespace mocapdb {

std::vector<std::pair<Eigen::Index, Eigen::Index>> PhaseCheck::below(double threshold) const {
    std::vector<std::pair<Eigen::Index, Eigen::Index>> out;
    for (Eigen::Index t = 0; t < share.size(); ++t) {
        if (!(share[t] < threshold)) continue;
        if (!out.empty() && out.back().second == t - 1) {
            out.back().second = t;
        } else {
            out.push_back({t, t});
        }
    }
    return out;
}

PhaseCheck check_phase(const std::vector<Clip>& samples, const AlignedSet& aligned,
                       const std::vector<std::string>& feet, double passing_cm) {
    if (samples.empty() || static_cast<Eigen::Index>(samples.size()) != aligned.samples())
        throw InvalidArgument("check_phase: " + std::to_string(samples.size()) + " samples for an aligned set of " +
                              std::to_string(aligned.samples()));
    PhaseCheck out;
    const Skeleton& s = *samples.front().skeleton;
    out.feet = feet.empty() ? default_feet(s) : feet;
    if (out.feet.size() != 2) throw InvalidArgument("check_phase: expected two feet (left, right)");
    const Eigen::Index frames = aligned.frames(), n = aligned.samples();
    out.forward.resize(frames, n);
    for (Eigen::Index i = 0; i < n; ++i) {
        const Clip& c = samples[static_cast<std::size_t>(i)];
        const VecX lead = forward_foot_separation(c, out.feet);  // left ahead of right, cm
        for (Eigen::Index t = 0; t < frames; ++t) {
            const auto f = static_cast<Eigen::Index>(
                std::clamp(std::lround(aligned.warps(t, i)), 0L, static_cast<long>(c.frame_count()) - 1));
            out.forward(t, i) = lead[f] > passing_cm ? 1 : lead[f] < -passing_cm ? -1 : 0;
        }
    }
    out.share.resize(frames);
    for (Eigen::Index t = 0; t < frames; ++t) {
        const Eigen::Index left = (out.forward.row(t).array() > 0).count();
        const Eigen::Index right = (out.forward.row(t).array() < 0).count();
        out.share[t] =
            left + right == 0 ? 1.0 : static_cast<double>(std::max(left, right)) / static_cast<double>(left + right);
    }
    out.min = out.share.minCoeff();
    out.mean = out.share.mean();
    return out;
}

}  // namespace mocapdb
