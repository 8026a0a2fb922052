#include "mocapdb/dataset/motion_set.hpp"

#include "mocapdb/core/error.hpp"

namespace mocapdb {

void validate(const MotionSet& set) {
    const std::string who = "motion set '" + set.name + "'";
    if (set.name.empty()) throw InvalidArgument("motion set: empty name");
    if (set.samples.empty()) throw InvalidArgument(who + ": no samples");
    for (std::size_t i = 0; i < set.samples.size(); ++i) {
        const SampleRef& s = set.samples[i];
        if (s.clip.empty()) throw InvalidArgument(who + ": sample " + std::to_string(i) + " names no clip");
        if (s.end < s.begin + 2)
            throw InvalidArgument(who + ": sample " + std::to_string(i) + " (" + s.clip + " [" +
                                  std::to_string(s.begin) + ", " + std::to_string(s.end) +
                                  ")) has fewer than 2 frames");
    }
    const auto n = static_cast<Eigen::Index>(set.samples.size());
    const auto p = static_cast<Eigen::Index>(set.parameter_names.size());
    if (set.parameter_units.size() != set.parameter_names.size())
        throw InvalidArgument(who + ": " + std::to_string(set.parameter_names.size()) + " parameter names but " +
                              std::to_string(set.parameter_units.size()) + " units");
    if (set.parameters.rows() != n || set.parameters.cols() != p)
        throw InvalidArgument(who + ": parameter matrix is " + std::to_string(set.parameters.rows()) + " by " +
                              std::to_string(set.parameters.cols()) + ", expected " + std::to_string(n) + " by " +
                              std::to_string(p) + " (samples by parameters)");
    if (!set.parameters.allFinite()) throw InvalidArgument(who + ": non-finite control parameter");
}

void check_distinguishable(const MotionSet& set) {
    const std::string who = "motion set '" + set.name + "'";
    if (set.samples.size() < 2)
        throw InvalidArgument(who + ": " + std::to_string(set.samples.size()) +
                              " sample; a set needs at least 2 (select more clips or a finer --segment)");
    if (set.parameters.cols() == 0) return;
    const auto first = set.parameters.row(0);
    for (Eigen::Index i = 1; i < set.parameters.rows(); ++i)
        if (set.parameters.row(i) != first) return;
    throw InvalidArgument(who + ": every sample has the same parameters, so synthesis could not tell them apart "
                          "(give parameters that differ between the samples)");
}

}  // namespace mocapdb
