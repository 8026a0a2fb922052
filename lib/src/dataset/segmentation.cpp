#include "mocapdb/dataset/segmentation.hpp"

#include "mocapdb/core/error.hpp"

namespace mocapdb {

std::vector<SampleRef> gait_cycles(const Clip& clip, const std::string& clip_id, const GaitCycleOptions& options) {
    if (!(options.min_seconds > 0 && options.max_seconds >= options.min_seconds))
        throw InvalidArgument("gait cycles: need 0 < min_seconds <= max_seconds");
    const auto contact = foot_contacts(clip, options.contacts);
    std::vector<std::size_t> touchdowns;
    for (Eigen::Index f = 1; f < contact.cols(); ++f)
        if (contact(0, f) && !contact(0, f - 1)) touchdowns.push_back(static_cast<std::size_t>(f));
    std::vector<SampleRef> out;
    for (std::size_t k = 0; k + 1 < touchdowns.size(); ++k) {
        const double seconds = static_cast<double>(touchdowns[k + 1] - touchdowns[k]) / clip.frame_rate;
        if (seconds < options.min_seconds || seconds > options.max_seconds) continue;
        out.push_back({clip_id, touchdowns[k], touchdowns[k + 1] + 1});
    }
    return out;
}

std::vector<SampleRef> fixed_windows(const Clip& clip, const std::string& clip_id, std::size_t length, std::size_t hop) {
    if (length < 2 || hop < 1) throw InvalidArgument("fixed windows: need length >= 2 frames and hop >= 1");
    std::vector<SampleRef> out;
    for (std::size_t b = 0; b + length <= clip.frame_count(); b += hop) out.push_back({clip_id, b, b + length});
    return out;
}

}  // namespace mocapdb
