#include "mocapdb/dataset/segmentation.hpp"

#include <algorithm>
#include <cmath>

#include "mocapdb/core/error.hpp"
#include "mocapdb/dataset/gait_phase.hpp"

namespace mocapdb {

std::vector<SampleRef> gait_cycles(const Clip& clip, const std::string& clip_id, const GaitCycleOptions& options) {
    if (!(options.min_seconds > 0 && options.max_seconds >= options.min_seconds))
        throw InvalidArgument("gait cycles: need 0 < min_seconds <= max_seconds");
    const std::vector<std::size_t> passes = left_foot_passes(forward_foot_separation(clip, options.feet));
    if (passes.size() < 2) return {};
    std::vector<std::size_t> lengths;
    for (std::size_t k = 0; k + 1 < passes.size(); ++k) lengths.push_back(passes[k + 1] - passes[k]);
    std::vector<std::size_t> sorted = lengths;
    std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2), sorted.end());
    const double median = static_cast<double>(sorted[sorted.size() / 2]);
    std::vector<SampleRef> out;
    for (std::size_t k = 0; k < lengths.size(); ++k) {
        const double frames = static_cast<double>(lengths[k]);
        const double seconds = frames / clip.frame_rate;
        if (seconds < options.min_seconds || seconds > options.max_seconds) continue;
        // A missed pass (a stop, a turn on the spot) joins two cycles; a spurious one halves one.
        if (frames > 1.5 * median || frames < median / 1.5) continue;
        out.push_back({clip_id, passes[k], passes[k + 1] + 1});
    }
    return spread_evenly(out, options.max_per_clip);
}

std::vector<SampleRef> flight_window(const Clip& clip, const std::string& clip_id, const FlightWindowOptions& options) {
    const auto valid = [](double seconds) { return seconds >= 0.0 && seconds <= 3600.0; };
    if (!valid(options.before_seconds) || !valid(options.after_seconds))
        throw InvalidArgument("flight window: the margins before take-off and after landing must be 0 to 3600 s");
    const std::optional<Flight> flight = longest_flight(foot_contacts(clip, options.contacts));
    if (!flight) return {};
    const auto margin = [&](double seconds) {
        return static_cast<Eigen::Index>(std::lround(seconds * clip.frame_rate));
    };
    const Eigen::Index frames = static_cast<Eigen::Index>(clip.frame_count());
    const Eigen::Index begin = std::max<Eigen::Index>(0, flight->takeoff - margin(options.before_seconds));
    const Eigen::Index end = std::min(frames, flight->landing + margin(options.after_seconds) + 1);
    return {{clip_id, static_cast<std::size_t>(begin), static_cast<std::size_t>(end)}};
}

std::vector<SampleRef> spread_evenly(const std::vector<SampleRef>& all, std::size_t keep) {
    if (keep == 0 || all.size() <= keep) return all;
    if (keep == 1) return {all[(all.size() - 1) / 2]};
    std::vector<SampleRef> out;
    for (std::size_t k = 0; k < keep; ++k) {
        const double pos = static_cast<double>(k) * static_cast<double>(all.size() - 1) / static_cast<double>(keep - 1);
        out.push_back(all[static_cast<std::size_t>(std::lround(pos))]);
    }
    return out;
}

std::vector<SampleRef> fixed_windows(const Clip& clip, const std::string& clip_id, std::size_t length,
                                     std::size_t hop) {
    if (length < 2 || hop < 1) throw InvalidArgument("fixed windows: need length >= 2 frames and hop >= 1");
    std::vector<SampleRef> out;
    for (std::size_t b = 0; b + length <= clip.frame_count(); b += hop) out.push_back({clip_id, b, b + length});
    return out;
}

}  // namespace mocapdb
